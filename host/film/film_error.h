// film_error.h: error estimates from the film's whole-sample statistics: per pixel (for
// adaptive sampling and the "error" AOV) and for the whole film (for --stats and the
// --error target). The film estimate uses the same definition as the true relative RMSE
// against a converged reference, so the benchmark can compare the two.
#pragma once
#include <algorithm>
#include <cmath>
#include <vector>

#include "cl/include/film.h"
#include "host/ocl/host_memory.h"

namespace rd {

// The film's pixels: page-aligned, so that the device's film buffer is this memory
// itself on a CPU device (a read of the film there copies nothing).
using FilmPixels = HostVector<PixelAccum>;

// Per-pixel statistics derived from the film sums.
struct PixelEstimate {
    float mean = 0;     // mean of the colour channels
    float stdError = 0; // standard error of the mean (0 with fewer than two samples)
};
// (Inline: the planner takes pixelMean of every pixel a pass changed; its relative
// errors come from the batch form of pixelStdError, film_error_batch.h, which must give
// the same bits.)
inline float pixelMean(const PixelAccum& p) {
    if (p.count == 0) return 0.0f;
    return float((double(p.sum.x) + p.sum.y + p.sum.z) / (3.0 * double(p.count)));
}  // estimatePixel(p).mean alone (the same bits), without the variance

// The standard error of the pixel's mean: the variance of the mean per channel (sum of
// squared deviations / (n - 1) / n), averaged over the three colour channels; in double,
// as the sums of squares cancel. Only for two samples or more.
inline float pixelStdError(const PixelAccum& p) {
    const double n = p.count, inv = 1.0 / n;
    double dev = 0;
    const float* s = &p.sum.x;
    const float* q = &p.sum_sq.x;
    for (int c = 0; c < 3; ++c) {
        const double m = s[c] * inv;
        dev += std::max(0.0, q[c] - n * m * m);
    }
    return float(std::sqrt(dev / (3.0 * n * (n - 1.0))));
}

inline PixelEstimate estimatePixel(const PixelAccum& p) {
    PixelEstimate e;
    if (p.count == 0) return e;
    e.mean = pixelMean(p);
    if (p.count >= 2) e.stdError = pixelStdError(p);
    return e;
}

// The squared error of the pixel's mean from its two replicates (the Sobol sampler's
// even and odd samples, film.h sum_odd: independent estimates of the same mean, of nA and
// nB samples): per channel (mA - mB)^2 nA nB / n^2, whose expectation is the variance of
// the pixel's mean (for n samples of one kind, var(mA - mB) = v (1/nA + 1/nB) and the
// mean's is v / n), averaged over the three colour channels. Unlike the samples' spread
// it holds for stratified samples, each replicate being unbiased on its own. Negative
// without samples of both replicates.
inline double replicateVariance(const PixelAccum& p) {
    const double nB = p.sum_odd.w, nA = double(p.count) - nB;
    if (nA < 1.0 || nB < 1.0) return -1.0;
    const double w = nA * nB / ((nA + nB) * (nA + nB));
    const float* s = &p.sum.x;
    const float* odd = &p.sum_odd.x;
    double v = 0;
    for (int c = 0; c < 3; ++c) {
        const double d = (double(s[c]) - odd[c]) / nA - double(odd[c]) / nB;
        v += d * d;
    }
    return v * w / 3.0;
}

// The film's relative error: sqrt(mean over pixels of the variance of the pixel mean)
// divided by the mean pixel value; the same definition as the true relative RMSE against
// a reference, so the two can be compared. Negative when no pixel has two samples.
// Two estimates of that variance:
struct FilmError {
    double spread = -1;      // from the samples' spread: independent samples
    double replicates = -1;  // from the replicates (replicateVariance): the Sobol sampler
    // The one that holds for the sampler, and how far the spread overstates it (the
    // planner's per-pixel errors come from the spread: 1 for independent samples).
    double of(bool sobol) const { return sobol ? replicates : spread; }
    double spreadOverstates(bool sobol) const {
        return sobol && spread > 0 && replicates > 0 ? std::max(1.0, spread / replicates)
                                                     : 1.0;
    }
};
// Over every pixel; or over one batch of kPixelBatch pixels in every `batchStride` (a
// film-wide ratio such as spreadOverstates, from a spread-out share of the work).
FilmError estimateFilmErrors(const FilmPixels& film, size_t batchStride = 1);
// The same from each batch's sums (film_error_batch.h), added in batch order: the device's
// (cl/kernels/film_sums.cl) give the same value.
struct FilmErrorSums;
FilmError filmErrorOfBatches(const std::vector<FilmErrorSums>& batches);

// x rounded down to a grid of `steps` points an octave (2^(k / steps)): a threshold that
// moves only when x does by a step (the brightness floor; the planner's Sobol ratio).
template <class T>
T roundDownOnOctaveGrid(T x, T steps) {
    return std::exp2(std::floor(std::log2(x) * steps) / steps);
}

// Per-pixel relative error as used for refinement: the standard error over the larger of
// the pixel's mean and a floor, a tenth of the image's mean brightness
// (relativeErrorFloor), so that nearly black pixels do not soak up the samples. The floor
// moves on a grid of 2^(1/8) steps, rounded down (at most 8% under a tenth of the mean):
// each time it falls the planner must visit every pixel, and the mean drifts by parts in
// a million from pass to pass (SPD tetra at 9 samples a pixel: three such visits of 2-3 ms
// each in its tail, for nothing).
std::vector<float> pixelRelativeErrors(const FilmPixels& film);
float relativeErrorFloor(const FilmPixels& film);
// The same from the sum of the sampled pixels' means and their number (a planner that
// keeps the sum up to date pass by pass).
float relativeErrorFloorOf(double meanSum, double pixels);
inline float pixelRelativeError(const PixelAccum& p, float floor) {
    PixelEstimate e = estimatePixel(p);
    return e.stdError / std::max(e.mean, floor);
}

}  // namespace rd
