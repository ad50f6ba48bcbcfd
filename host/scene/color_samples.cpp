// color_samples.cpp: the scene's colour channels and their conversions (color_samples.h).
#include "color_samples.h"

#include <algorithm>

namespace rd {

bool ColorSamples::isRgb() const {
    const ColorSamples rgb;
    return n == 3 && toRgb == rgb.toRgb && fromRgb == rgb.fromRgb;
}

bool ColorSamples::set(const std::vector<float>& nRGB, const std::vector<float>& RGBn) {
    const size_t k = nRGB.size() / 3;
    if (k < 1 || k > size_t(kMaxChannels) || nRGB.size() != 3 * k || RGBn.size() != 3 * k)
        return false;
    n = int(k);
    if (k > 3) {
        toRgb = nRGB;
        fromRgb = RGBn;
        return true;
    }
    toRgb.assign(9, 0.0f);
    fromRgb.assign(9, 0.0f);
    for (size_t i = 0; i < 3 * k; ++i) toRgb[i] = nRGB[i];
    for (size_t j = 0; j < 3; ++j)
        for (size_t i = 0; i < 3; ++i)
            fromRgb[3 * j + i] = RGBn[j * k + std::min(i, k - 1)];
    return true;
}

// c[0..rows) * m (rows x cols, row-vector convention) into c[0..cols), as the device's
// rsl_color_rgb and rsl_rgb_color do
static void mulRows(const std::vector<float>& m, size_t rows, float* c) {
    const size_t cols = m.size() / rows;
    std::vector<float> in(c, c + rows);
    for (size_t j = 0; j < cols; ++j) {
        float v = 0.0f;
        for (size_t i = 0; i < rows; ++i) v += in[i] * m[i * cols + j];
        c[j] = v;
    }
}

void ColorSamples::fromRgbValues(float* c) const {
    mulRows(fromRgb, 3, c);
}

void ColorSamples::toRgbValues(float* c) const {
    mulRows(toRgb, size_t(slots()), c);
}

}  // namespace rd
