// film_error_batch.h: pixelRelativeError for a batch of pixels at once, on the widest
// vectors the host has (the sample planner tests every pixel of the frame in some passes).
#pragma once
#include <cstddef>
#include <cstdint>

#include "cl/include/film.h"

namespace rd {

constexpr size_t kPixelBatch = RT_FILM_BATCH;

// A batch's pixels' film sums laid out by channel (n: the sample count, s: the sums, q:
// the sums of squares, mean: pixelMean), as the film holds them: the vector loops widen
// them to double (exactly), where gathering them as doubles took a scalar conversion
// each.
struct PixelSumsBatch {
    alignas(64) uint32_t n[kPixelBatch];
    alignas(64) float s[3][kPixelBatch], q[3][kPixelBatch];
    alignas(64) float mean[kPixelBatch];
};

// relErr[j] = pixelRelativeError of pixel j against `floor`: the same bits (0 for a
// pixel with fewer than two samples).
void relativeErrors(const PixelSumsBatch& b, float floor, float* relErr);

// estimateFilmErrors' sums over some pixels: of the squared standard errors (pixels with
// two samples or more) and of the means (pixels with samples), each taken as
// pixelStdError and pixelMean give them.
// Also the sums of the replicate estimate (film_error.h): the squared error of each
// pixel's mean from the difference of its even and odd samples' means, over the pixels
// with samples of both.
struct FilmErrorSums {
    double var = 0, mean = 0, replicateVar = 0;
    size_t withVar = 0, withMean = 0, withReplicates = 0;
};
// Adds `count` (at most kPixelBatch) pixels' parts to `sums`, in pixel order.
void addFilmErrorSums(const PixelAccum* pixels, size_t count, FilmErrorSums& sums);

}  // namespace rd
