// film_error.cpp: per-pixel and film error estimates.
#include "film_error.h"

#include <algorithm>
#include <cmath>

#include "film_error_batch.h"
#include "run_in_parts.h"

namespace rd {

// (Sums by batch of pixels, the batches' sums added in order: the same value for any
// number of threads. A 512x512 film took 2.3 ms pixel by pixel on one core, the end of
// every frame; now a batch's divisions and square roots are vector operations.)
FilmError estimateFilmErrors(const FilmPixels& film, size_t batchStride) {
    const size_t batches =
        (film.size() + kPixelBatch * batchStride - 1) / (kPixelBatch * batchStride);
    std::vector<FilmErrorSums> part(batches);
    // (threads only where they pay for their start: a large film)
    const size_t pixels = film.size() / batchStride;
    runInParts(batches, pixels < 65536 ? 1 : hostThreads(),
               [&](size_t begin, size_t end, size_t) {
                   for (size_t i = begin; i < end; ++i) {
                       const size_t first = i * kPixelBatch * batchStride;
                       addFilmErrorSums(&film[first],
                                        std::min(kPixelBatch, film.size() - first),
                                        part[i]);
                   }
               });
    return filmErrorOfBatches(part);
}

FilmError filmErrorOfBatches(const std::vector<FilmErrorSums>& part) {
    FilmErrorSums sum;
    for (const FilmErrorSums& s : part) {
        sum.var += s.var, sum.mean += s.mean, sum.replicateVar += s.replicateVar;
        sum.withVar += s.withVar, sum.withMean += s.withMean,
            sum.withReplicates += s.withReplicates;
    }
    FilmError e;
    if (sum.mean <= 0) return e;
    const double mean = sum.mean / double(sum.withMean);
    if (sum.withVar > 0) e.spread = std::sqrt(sum.var / double(sum.withVar)) / mean;
    if (sum.withReplicates > 0)
        e.replicates = std::sqrt(sum.replicateVar / double(sum.withReplicates)) / mean;
    return e;
}

float relativeErrorFloor(const FilmPixels& film) {
    double meanSum = 0;
    size_t n = 0;
    for (const PixelAccum& p : film)
        if (p.count) meanSum += pixelMean(p), ++n;
    return relativeErrorFloorOf(meanSum, double(n));
}

float relativeErrorFloorOf(double meanSum, double pixels) {
    const float tenth = std::max(1e-4f, 0.1f * float(pixels > 0 ? meanSum / pixels : 0.0));
    return roundDownOnOctaveGrid(tenth, 8.0f);
}

std::vector<float> pixelRelativeErrors(const FilmPixels& film) {
    const float floor = relativeErrorFloor(film);
    std::vector<float> out(film.size(), 0.0f);
    for (size_t i = 0; i < film.size(); ++i) out[i] = pixelRelativeError(film[i], floor);
    return out;
}

}  // namespace rd
