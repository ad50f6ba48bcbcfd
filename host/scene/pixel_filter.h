// pixel_filter.h: RI pixel filters (PixelFilter "gaussian" 2 2 ...) as the distribution
// of each sample's place about its pixel's centre (filter importance sampling, as Cycles
// does): a sample lands at x with probability |f(x)| / the integral of |f|, so a pixel's
// plain mean of its samples is the filtered image, and adaptive sampling and the error
// estimates stay per pixel. Filters are separable (f(x, y) = g(x) g(y), RI's
// catmull-rom taken in its separable form), or radial (PRMan's disk and bessel: f(r) of
// the distance from the centre, stretched along y when the widths differ), sampled by
// distance (from |f(r)| r) and a uniform angle; where the filter is negative a sample
// counts negatively, and every sample weighs the integral of |f| over that of f.
#pragma once
#include <string>

#include "cl/include/scene_types.h"

namespace rd {

// The filters known: box, triangle, gaussian, catmull-rom (and separable-catmull-rom),
// sinc, mitchell, blackman-harris, lanczos; disk and bessel (radial).
bool pixelFilterKnown(const std::string& name);
bool pixelFilterRadial(const std::string& name);

// g(x) of a filter `width` pixels wide (its support [-width / 2, width / 2]), x in
// pixels.
double pixelFilter1D(const std::string& name, double x, double width);

// f(x, y) of a filter xwidth by ywidth pixels (separable: g(x) g(y); radial: f of
// hypot(x, y xwidth / ywidth) within xwidth / 2).
double pixelFilter2D(const std::string& name, double x, double y, double xwidth,
                     double ywidth);

// Writes the camera's filter fields (Camera::filter_*) for a filter and its widths.
// Returns false (and leaves a box of the widths) for a filter not known, or one whose
// integral is not positive, or that changes sign more than RT_FILTER_FLIPS times along
// an axis (a sinc or lanczos wider than about 16 pixels).
bool setCameraFilter(Camera& cam, const std::string& name, float xwidth, float ywidth);

}  // namespace rd
