// film_error.cpp: per-pixel and film error estimates.
#include "film_error.h"

#include <algorithm>
#include <cmath>

namespace rd {

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

std::vector<float> pixelRelativeErrors(const FilmPixels& film) {
    const float floor = relativeErrorFloor(film);
    std::vector<float> out(film.size(), 0.0f);
    for (size_t i = 0; i < film.size(); ++i) out[i] = pixelRelativeError(film[i], floor);
    return out;
}

}  // namespace rd
