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
    const double m0 = double(b.s[0][j]) * inv, m1 = double(b.s[1][j]) * inv,
                 m2 = double(b.s[2][j]) * inv;
    double dev = std::max(0.0, double(b.q[0][j]) - n * m0 * m0);
    dev += std::max(0.0, double(b.q[1][j]) - n * m1 * m1);
    dev += std::max(0.0, double(b.q[2][j]) - n * m2 * m2);
    return float(std::sqrt(dev / (3.0 * n * (n - 1.0))));
}

}  // namespace

__attribute__((target_clones("avx512f", "avx2", "default")))
void relativeErrors(const PixelSumsBatch& b, float floor, float* __restrict relErr) {
    for (size_t j = 0; j < kPixelBatch; ++j)
        relErr[j] = (b.n[j] >= 2 ? stdErrorOf(b, j) : 0.0f) / std::max(b.mean[j], floor);
}

namespace {

// The pixels' means and standard errors (pixelMean and pixelStdError: the same bits;
// meaningless for fewer samples than those need).
__attribute__((target_clones("avx512f", "avx2", "default")))
void meansAndErrors(const PixelSumsBatch& b, float* __restrict mean, float* __restrict stdError) {
    for (size_t j = 0; j < kPixelBatch; ++j) {
        mean[j] = float((double(b.s[0][j]) + double(b.s[1][j]) + double(b.s[2][j])) /
                        (3.0 * double(b.n[j])));
        stdError[j] = stdErrorOf(b, j);
    }
}

// The replicates' sample counts and the odd samples' sums (PixelAccum::sum_odd).
struct ReplicateBatch {
    alignas(64) float nB[kPixelBatch], odd[3][kPixelBatch];
};

// The pixels' replicateVariance (the same bits; -1 without samples in both replicates):
// scalar, its six double divisions a pixel were most of the film estimate's time (SPD
// tetra at 9 samples a pixel: 1.9 ms at the end of each frame).
__attribute__((target_clones("avx512f", "avx2", "default")))
void replicateVariances(const PixelSumsBatch& b, const ReplicateBatch& r,
                        double* __restrict var) {
    for (size_t j = 0; j < kPixelBatch; ++j) {
        const double nB = r.nB[j], nA = double(b.n[j]) - nB;
        const double w = nA * nB / ((nA + nB) * (nA + nB));
        const double o0 = r.odd[0][j], o1 = r.odd[1][j], o2 = r.odd[2][j];
        const double d0 = (double(b.s[0][j]) - o0) / nA - o0 / nB;
        const double d1 = (double(b.s[1][j]) - o1) / nA - o1 / nB;
        const double d2 = (double(b.s[2][j]) - o2) / nA - o2 / nB;
        const double v = ((0.0 + d0 * d0) + d1 * d1) + d2 * d2;
        var[j] = (nA >= 1.0) & (nB >= 1.0) ? v * w / 3.0 : -1.0;
    }
}

}  // namespace

void addFilmErrorSums(const PixelAccum* pixels, size_t count, FilmErrorSums& sums) {
    PixelSumsBatch b;
    ReplicateBatch r;
    for (size_t j = 0; j < kPixelBatch; ++j) {
        const PixelAccum& p = pixels[std::min(j, count - 1)];  // (a short batch: repeats)
        b.n[j] = p.count;
        b.s[0][j] = p.sum.x, b.s[1][j] = p.sum.y, b.s[2][j] = p.sum.z;
        b.q[0][j] = p.sum_sq.x, b.q[1][j] = p.sum_sq.y, b.q[2][j] = p.sum_sq.z;
        r.nB[j] = p.sum_odd.w;
        r.odd[0][j] = p.sum_odd.x, r.odd[1][j] = p.sum_odd.y, r.odd[2][j] = p.sum_odd.z;
    }
    alignas(64) float mean[kPixelBatch], stdError[kPixelBatch];
    alignas(64) double replicateVar[kPixelBatch];
    meansAndErrors(b, mean, stdError);
    replicateVariances(b, r, replicateVar);
    // (in locals: through `sums` each count was a load and a store a pixel)
    FilmErrorSums s = sums;
    for (size_t j = 0; j < count; ++j) {
        if (pixels[j].count == 0) continue;
        s.mean += mean[j];
        ++s.withMean;
        if (pixels[j].count >= 2) {
            s.var += double(stdError[j]) * stdError[j];
            ++s.withVar;
        }
        if (const double v = replicateVar[j]; v >= 0) {
            s.replicateVar += v;
            ++s.withReplicates;
        }
    }
    sums = s;
}

}  // namespace rd
