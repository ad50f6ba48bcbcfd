// pixel_filter.cpp: the pixel filters and their sampling tables (pixel_filter.h).
#include "pixel_filter.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace rd {

namespace {
constexpr double kPi = 3.14159265358979323846;

double sinc(double x) {
    return x == 0 ? 1.0 : std::sin(kPi * x) / (kPi * x);
}

// The cubic of Mitchell and Netravali with B = C = 1/3, t in [0, 2).
double mitchell(double t) {
    const double B = 1.0 / 3.0, C = 1.0 / 3.0;
    t = std::fabs(t);
    if (t < 1)
        return ((12 - 9 * B - 6 * C) * t * t * t + (-18 + 12 * B + 6 * C) * t * t +
                (6 - 2 * B)) /
               6;
    if (t < 2)
        return ((-B - 6 * C) * t * t * t + (6 * B + 30 * C) * t * t +
                (-12 * B - 48 * C) * t + (8 * B + 24 * C)) /
               6;
    return 0;
}

// One axis's table: the inverse cumulative |g| at u = k / RT_FILTER_TABLE, g's sign at
// the support's start and the u where it changes, and the integral of |g| over that of g
// (0 when that is not > 0, or g changes sign more than RT_FILTER_FLIPS times).
double fillAxis(const std::string& name, double width, float* icdf,
                uint32_t* negativeStart, float* flips) {
    constexpr int kSteps = 8192;  // the integration grid over the support
    const double half = width / 2, h = width / kSteps;
    std::vector<double> cdf(kSteps + 1, 0.0);
    double signedSum = 0;
    for (int i = 0; i < kSteps; ++i) {  // (midpoint rule per step)
        const double g = pixelFilter1D(name, -half + (i + 0.5) * h, width);
        cdf[size_t(i) + 1] = cdf[size_t(i)] + std::fabs(g) * h;
        signedSum += g * h;
    }
    const double total = cdf[kSteps];
    if (!(signedSum > 0) || !(total > 0)) return 0;
    int i = 0;
    for (int k = 0; k <= RT_FILTER_TABLE; ++k) {
        const double target = total * k / RT_FILTER_TABLE;
        while (i < kSteps - 1 && cdf[size_t(i) + 1] < target) ++i;
        const double span = cdf[size_t(i) + 1] - cdf[size_t(i)];
        const double f =
            span > 0 ? std::clamp((target - cdf[size_t(i)]) / span, 0.0, 1.0) : 0.0;
        icdf[k] = float(-half + (i + f) * h);
    }
    icdf[0] = float(-half), icdf[RT_FILTER_TABLE] = float(half);
    for (int k = RT_FILTER_TABLE + 1; k < RT_FILTER_TABLE + 4; ++k) icdf[k] = float(half);
    // The sign changes, at the u of the cumulative |g| where g crosses zero.
    int nflips = 0, sign = 0;
    for (int f = 0; f < RT_FILTER_FLIPS; ++f) flips[f] = 2.0f;  // (never reached)
    *negativeStart = 0;
    for (int j = 0; j < kSteps; ++j) {
        const double g = pixelFilter1D(name, -half + (j + 0.5) * h, width);
        const int s = g > 0 ? 1 : g < 0 ? -1 : 0;
        if (s == 0) continue;
        if (sign == 0) {
            *negativeStart = s < 0;
        } else if (s != sign) {
            if (nflips == RT_FILTER_FLIPS) return 0;
            flips[nflips++] = float(cdf[size_t(j)] / total);
        }
        sign = s;
    }
    return total / signedSum;
}
}  // namespace

bool pixelFilterKnown(const std::string& name) {
    for (const char* n :
         {"box", "triangle", "gaussian", "catmull-rom", "separable-catmull-rom", "sinc",
          "mitchell", "blackman-harris", "lanczos"})
        if (name == n) return true;
    return false;
}

double pixelFilter1D(const std::string& name, double x, double width) {
    const double half = width / 2, r = std::fabs(x);
    if (r > half) return 0;
    if (name == "triangle") return 1 - r / half;
    if (name == "gaussian") {  // RI: x scaled by 2 / width, exp(-2 x^2)
        const double t = 2 * x / width;
        return std::exp(-2 * t * t);
    }
    if (name == "catmull-rom" || name == "separable-catmull-rom") {  // in pixels
        if (r < 1) return 1.5 * r * r * r - 2.5 * r * r + 1;
        if (r < 2) return -0.5 * r * r * r + 2.5 * r * r - 4 * r + 2;
        return 0;
    }
    if (name == "sinc")
        return sinc(x);  // RI: sin(pi x) / (pi x) in pixels, cut at the width
    if (name == "mitchell")
        return mitchell(4 * x / width);  // the cubic's [-2, 2] on the width
    if (name == "blackman-harris") {
        const double t = x / width + 0.5;
        return 0.35875 - 0.48829 * std::cos(2 * kPi * t) +
               0.14128 * std::cos(4 * kPi * t) - 0.01168 * std::cos(6 * kPi * t);
    }
    if (name == "lanczos") return sinc(x) * sinc(x / half);
    return 1;  // box
}

bool setCameraFilter(Camera& cam, const std::string& name, float xwidth, float ywidth) {
    cam.filter_width[0] = xwidth, cam.filter_width[1] = ywidth;
    cam.filter_weight = 1.0f;
    cam.filter_table = 0;
    if (name == "box") return true;
    const double rx = fillAxis(name, xwidth, cam.filter_icdf[0],
                               &cam.filter_negative_start[0], cam.filter_flips[0]);
    const double ry = fillAxis(name, ywidth, cam.filter_icdf[1],
                               &cam.filter_negative_start[1], cam.filter_flips[1]);
    if (!(rx > 0) || !(ry > 0)) return false;
    cam.filter_weight = float(rx * ry);
    cam.filter_table = 1;
    return true;
}

}  // namespace rd
