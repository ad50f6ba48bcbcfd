// numerics_util.h: what the numerics cases share: the report line each case prints, a
// render that keeps the diagnostics it produced, and small RIB builders.
#pragma once
#include <string>

#include "render_harness.h"

namespace rd::numerics {

// Prints `NUMERICS case=<name> tolerance=<tol> measured=<measured>` and returns
// measured <= tol (a NaN measurement fails).
bool report(const std::string& name, double tolerance, double measured);

// Renders like rd::test::renderRib and also returns what the reader, builder and
// renderer printed (one diagnostic per line) and how many warnings there were.
struct Diagnosed {
    rd::test::Rendered image;
    std::string messages;
    int warnings = 0, errors = 0;
};
Diagnosed renderWithDiagnostics(const std::string& rib, const RenderSettings& settings = {});

// Occurrences of `needle` in `text`.
int countOf(const std::string& text, const std::string& needle);

// "Format n n 1 / PixelSamples s s / Projection perspective fov"
std::string camera(int res, double fovDeg, int spp);
// A square polygon of half-size h in the plane z = z (facing -z, the camera).
std::string squareAtZ(double z, double h = 50);
// Largest |channel| of a pixel over the image, and whether any channel is NaN or Inf.
double maxAbs(const rd::test::Rendered& img);
bool allFinite(const rd::test::Rendered& img);

}  // namespace rd::numerics
