// film_error.h: error estimates from the film's whole-sample statistics: per pixel (for
// adaptive sampling and the "error" AOV) and for the whole film (for --stats and the
// --error target). The film estimate uses the same definition as the true relative RMSE
// against a converged reference, so the benchmark can compare the two.
#pragma once
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
PixelEstimate estimatePixel(const PixelAccum& p);
// estimatePixel(p).mean alone (the same bits), without the variance.
float pixelMean(const PixelAccum& p);

// The film's relative error: sqrt(mean over pixels of the variance of the pixel mean)
// divided by the mean pixel value; the same definition as the true relative RMSE against
// a reference, so the two can be compared. Negative when no pixel has two samples.
double estimateFilmError(const FilmPixels& film);

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
float pixelRelativeError(const PixelAccum& p, float floor);

}  // namespace rd
