// pixel_filter.cpp: the pixel filters and their sampling tables (pixel_filter.h).
#include "pixel_filter.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <utility>
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

// g(x) of a filter `width` pixels wide, inside its support (x in pixels).
using Filter1D = double (*)(double x, double width);

double boxG(double, double) {
    return 1;
}
double triangleG(double x, double width) {
    return 1 - std::fabs(x) / (width / 2);
}
double gaussianG(double x, double width) {  // RI: x scaled by 2 / width, exp(-2 x^2)
    const double t = 2 * x / width;
    return std::exp(-2 * t * t);
}
double catmullRomG(double x, double) {  // in pixels
    const double r = std::fabs(x);
    if (r < 1) return 1.5 * r * r * r - 2.5 * r * r + 1;
    if (r < 2) return -0.5 * r * r * r + 2.5 * r * r - 4 * r + 2;
    return 0;
}
double sincG(double x, double) {
    return sinc(x);
}  // RI: in pixels, cut at the width
double mitchellG(double x, double width) {
    return mitchell(4 * x / width);
}  // [-2, 2]
double blackmanHarrisG(double x, double width) {
    const double t = x / width + 0.5;
    return 0.35875 - 0.48829 * std::cos(2 * kPi * t) + 0.14128 * std::cos(4 * kPi * t) -
           0.01168 * std::cos(6 * kPi * t);
}
double lanczosG(double x, double width) {
    return sinc(x) * sinc(x / (width / 2));
}

// Radial filters (PRMan's disk and bessel): f(r) of the distance r in pixels from the
// centre, the support a disc of radius xwidth / 2 stretched to an ellipse along y.
using FilterRadial = double (*)(double r);
double diskF(double) {
    return 1;
}
double besselF(double r) {  // jinc: 2 J1(pi r) / (pi r), 1 at the centre
    const double x = kPi * r;
    return x < 1e-8 ? 1.0 : 2 * std::cyl_bessel_j(1.0, x) / x;
}
FilterRadial radialNamed(const std::string& name) {
    return name == "disk" ? diskF : name == "bessel" ? besselF : nullptr;
}

// The filter of a name; null for one not known.
Filter1D filterNamed(const std::string& name) {
    static const std::pair<const char*, Filter1D> filters[] = {
        {"box", boxG},
        {"triangle", triangleG},
        {"gaussian", gaussianG},
        {"catmull-rom", catmullRomG},
        {"separable-catmull-rom", catmullRomG},
        {"sinc", sincG},
        {"mitchell", mitchellG},
        {"blackman-harris", blackmanHarrisG},
        {"lanczos", lanczosG}};
    for (const auto& [n, g] : filters)
        if (name == n) return g;
    return nullptr;
}

// One axis's table over [lo, hi]: the inverse cumulative |g| at u = k / RT_FILTER_TABLE,
// g's sign at the support's start and the u where it changes, and the integral of |g|
// over that of g (0 when that is not > 0, or g changes sign more than RT_FILTER_FLIPS
// times). One pass over g on a fine grid (midpoint rule per step).
template <class G>
double fillTable(const G& g, double lo, double hi, float* icdf, uint32_t* negativeStart,
                 float* flips) {
    constexpr int kSteps = 8192;
    const double h = (hi - lo) / kSteps;
    std::vector<double> cdf(kSteps + 1, 0.0), flipAt;
    double signedSum = 0;
    int sign = 0;
    *negativeStart = 0;
    for (int i = 0; i < kSteps; ++i) {
        const double v = g(lo + (i + 0.5) * h);
        cdf[size_t(i) + 1] = cdf[size_t(i)] + std::fabs(v) * h;
        signedSum += v * h;
        const int s = v > 0 ? 1 : v < 0 ? -1 : 0;
        if (s == 0) continue;
        if (sign == 0)
            *negativeStart = s < 0;
        else if (s != sign)
            flipAt.push_back(cdf[size_t(i)]);
        sign = s;
    }
    const double total = cdf[kSteps];
    if (!(signedSum > 0) || !(total > 0) || flipAt.size() > RT_FILTER_FLIPS) return 0;
    int i = 0;
    for (int k = 0; k <= RT_FILTER_TABLE; ++k) {
        const double target = total * k / RT_FILTER_TABLE;
        while (i < kSteps - 1 && cdf[size_t(i) + 1] < target) ++i;
        const double span = cdf[size_t(i) + 1] - cdf[size_t(i)];
        const double f =
            span > 0 ? std::clamp((target - cdf[size_t(i)]) / span, 0.0, 1.0) : 0.0;
        icdf[k] = float(lo + (i + f) * h);
    }
    icdf[0] = float(lo), icdf[RT_FILTER_TABLE] = float(hi);
    for (int k = RT_FILTER_TABLE + 1; k < RT_FILTER_TABLE + 4; ++k) icdf[k] = float(hi);
    for (size_t f = 0; f < RT_FILTER_FLIPS; ++f)  // (2: never reached)
        flips[f] = f < flipAt.size() ? float(flipAt[f] / total) : 2.0f;
    return total / signedSum;
}
double fillAxis(Filter1D g, double width, float* icdf, uint32_t* negativeStart,
                float* flips) {
    return fillTable([&](double x) { return g(x, width); }, -width / 2, width / 2, icdf,
                     negativeStart, flips);
}
}  // namespace

bool pixelFilterKnown(const std::string& name) {
    return filterNamed(name) != nullptr || radialNamed(name) != nullptr;
}

bool pixelFilterRadial(const std::string& name) {
    return radialNamed(name) != nullptr;
}

double pixelFilter1D(const std::string& name, double x, double width) {
    const Filter1D g = filterNamed(name);
    return std::fabs(x) > width / 2 ? 0 : g ? g(x, width) : 1;  // (unknown: a box)
}

double pixelFilter2D(const std::string& name, double x, double y, double xwidth,
                     double ywidth) {
    const FilterRadial f = radialNamed(name);
    if (!f) return pixelFilter1D(name, x, xwidth) * pixelFilter1D(name, y, ywidth);
    const double r = std::hypot(x, y * xwidth / ywidth);
    return r > xwidth / 2 ? 0 : f(r);
}

bool setCameraFilter(Camera& cam, const std::string& name, float xwidth, float ywidth) {
    cam.filter_width[0] = xwidth, cam.filter_width[1] = ywidth;
    cam.filter_weight = 1.0f;
    cam.filter_table = 0;
    if (const FilterRadial f = radialNamed(name)) {
        // the distance from the centre drawn from |f(r)| r (the disc's area element), the
        // angle uniform: table 0 over [0, xwidth / 2]
        const double ratio = fillTable(
            [&](double r) { return f(r) * r; }, 0.0, xwidth / 2.0, cam.filter_icdf[0],
            &cam.filter_negative_start[0], cam.filter_flips[0]);
        cam.filter_negative_start[1] = 0;  // (one table: the other axis never flips)
        std::fill(std::begin(cam.filter_flips[1]), std::end(cam.filter_flips[1]), 2.0f);
        if (!(ratio > 0)) return false;
        cam.filter_weight = float(ratio);
        cam.filter_table = 2;
        return true;
    }
    const Filter1D g = filterNamed(name);
    if (!g || g == boxG) return g != nullptr;
    const double rx = fillAxis(g, xwidth, cam.filter_icdf[0],
                               &cam.filter_negative_start[0], cam.filter_flips[0]);
    double ry = rx;
    if (ywidth != xwidth)
        ry = fillAxis(g, ywidth, cam.filter_icdf[1], &cam.filter_negative_start[1],
                      cam.filter_flips[1]);
    else {  // (the same axis: its table once)
        std::copy(std::begin(cam.filter_icdf[0]), std::end(cam.filter_icdf[0]),
                  cam.filter_icdf[1]);
        std::copy(std::begin(cam.filter_flips[0]), std::end(cam.filter_flips[0]),
                  cam.filter_flips[1]);
        cam.filter_negative_start[1] = cam.filter_negative_start[0];
    }
    if (!(rx > 0) || !(ry > 0)) return false;
    cam.filter_weight = float(rx * ry);
    cam.filter_table = 1;
    return true;
}

}  // namespace rd
