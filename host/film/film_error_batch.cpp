// film_error_batch.cpp: the batch form of pixelRelativeError. Built with errno and
// floating-point traps set aside (neither is looked at), so that the compiler turns the
// loop into vector divisions and square roots, and without fused multiply-adds, so that
// every clone computes the bits pixelStdError does (host/CMakeLists.txt).
#include "film_error_batch.h"

#include <algorithm>
#include <cmath>

namespace rd {

__attribute__((target_clones("avx512f", "avx2", "default")))
void relativeErrors(const PixelSumsBatch& b, float floor, float* __restrict relErr) {
    for (size_t j = 0; j < kPixelBatch; ++j) {
        const double n = b.n[j], inv = 1.0 / n;
        const double m0 = b.s[0][j] * inv, m1 = b.s[1][j] * inv, m2 = b.s[2][j] * inv;
        double dev = std::max(0.0, b.q[0][j] - n * m0 * m0);
        dev += std::max(0.0, b.q[1][j] - n * m1 * m1);
        dev += std::max(0.0, b.q[2][j] - n * m2 * m2);
        const float stdError = float(std::sqrt(dev / (3.0 * n * (n - 1.0))));
        relErr[j] = (n >= 2.0 ? stdError : 0.0f) / std::max(b.mean[j], floor);
    }
}

}  // namespace rd
