// film_error_batch.h: pixelRelativeError for a batch of pixels at once, on the widest
// vectors the host has (the sample planner tests every pixel of the frame in some passes).
#pragma once
#include <cstddef>

namespace rd {

constexpr size_t kPixelBatch = 64;

// A batch's pixels' film sums laid out by channel (n: the sample count, s: the sums, q:
// the sums of squares, mean: pixelMean).
struct PixelSumsBatch {
    alignas(64) double n[kPixelBatch], s[3][kPixelBatch], q[3][kPixelBatch];
    alignas(64) float mean[kPixelBatch];
};

// relErr[j] = pixelRelativeError of pixel j against `floor`: the same bits (0 for a
// pixel with fewer than two samples).
void relativeErrors(const PixelSumsBatch& b, float floor, float* relErr);

}  // namespace rd
