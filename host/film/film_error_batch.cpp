// film_error_batch.cpp: the batch forms of pixelRelativeError and of the film estimate's
// per-pixel terms. Built with errno and
// floating-point traps set aside (neither is looked at), so that the compiler turns the
// loop into vector divisions and square roots, and without fused multiply-adds, so that
// every clone computes the bits pixelStdError does (host/CMakeLists.txt).
#include "film_error_batch.h"

#include <algorithm>
#include <cmath>

#include "film_error.h"

namespace rd {

namespace {

// Pixel j's pixelStdError, the same bits (meaningless under two samples); inlined into each
// clone's loop, which it leaves vectorisable.
inline __attribute__((always_inline)) float stdErrorOf(const PixelSumsBatch& b, size_t j) {
    const double n = b.n[j], inv = 1.0 / n;
    const double m0 = b.s[0][j] * inv, m1 = b.s[1][j] * inv, m2 = b.s[2][j] * inv;
    double dev = std::max(0.0, b.q[0][j] - n * m0 * m0);
    dev += std::max(0.0, b.q[1][j] - n * m1 * m1);
    dev += std::max(0.0, b.q[2][j] - n * m2 * m2);
    return float(std::sqrt(dev / (3.0 * n * (n - 1.0))));
}

}  // namespace

__attribute__((target_clones("avx512f", "avx2", "default")))
void relativeErrors(const PixelSumsBatch& b, float floor, float* __restrict relErr) {
    for (size_t j = 0; j < kPixelBatch; ++j)
        relErr[j] = (b.n[j] >= 2.0 ? stdErrorOf(b, j) : 0.0f) / std::max(b.mean[j], floor);
}

namespace {

// The pixels' means and standard errors (pixelMean and pixelStdError: the same bits;
// meaningless for fewer samples than those need).
__attribute__((target_clones("avx512f", "avx2", "default")))
void meansAndErrors(const PixelSumsBatch& b, float* __restrict mean, float* __restrict stdError) {
    for (size_t j = 0; j < kPixelBatch; ++j) {
        mean[j] = float((b.s[0][j] + b.s[1][j] + b.s[2][j]) / (3.0 * b.n[j]));
        stdError[j] = stdErrorOf(b, j);
    }
}

}  // namespace

void addFilmErrorSums(const PixelAccum* pixels, size_t count, FilmErrorSums& sums) {
    PixelSumsBatch b;
    for (size_t j = 0; j < kPixelBatch; ++j) {
        const PixelAccum& p = pixels[std::min(j, count - 1)];  // (a short batch: repeats)
        b.n[j] = p.count;
        b.s[0][j] = p.sum.x, b.s[1][j] = p.sum.y, b.s[2][j] = p.sum.z;
        b.q[0][j] = p.sum_sq.x, b.q[1][j] = p.sum_sq.y, b.q[2][j] = p.sum_sq.z;
    }
    alignas(64) float mean[kPixelBatch], stdError[kPixelBatch];
    meansAndErrors(b, mean, stdError);
    for (size_t j = 0; j < count; ++j) {
        if (pixels[j].count == 0) continue;
        sums.mean += mean[j];
        ++sums.withMean;
        if (pixels[j].count >= 2) {
            sums.var += double(stdError[j]) * stdError[j];
            ++sums.withVar;
        }
        if (const double v = replicateVariance(pixels[j]); v >= 0) {
            sums.replicateVar += v;
            ++sums.withReplicates;
        }
    }
}

}  // namespace rd
