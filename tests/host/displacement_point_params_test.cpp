// displacement_point_params_test.cpp: primitive variables named like a parameter of the
// Displacement shader give it its value per point, as they do a surface shader's
// (rsl_abi.h, PER-POINT PARAMETERS: pv_dslot), bump mapped and truly displaced: a flat
// square lifted by a per-vertex height turns its normal by the slope of that height, and
// scenes whose displacements take no such values get no build option for them
// (true_displacement_test.cpp: a sphere pushed out by per-corner amounts).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "render/features.h"
#include "render_harness.h"

using rd::test::Rendered;
using rd::test::renderRib;

namespace {

std::string shaderPath() {
    static const char* const kShaders[][2] = {
        // P lifted along N by h (0 unless a primitive gives it)
        {"dpp_lift",
         "displacement dpp_lift(float h = 0) {\n"
         "    P += h * normalize(N);\n    N = calculatenormal(P);\n}\n"},
        // N . I: 1 where the surface faces the camera
        {"dpp_facing",
         "surface dpp_facing(float h = 0) {\n"
         "    Ci = abs(normalize(N) . normalize(I));\n    Oi = 1;\n}\n"},
        // the surface's own h, shaded by how the surface faces the camera: both
        // shaders take the value
        {"dpp_value",
         "surface dpp_value(float h = 0) {\n"
         "    Ci = h * abs(normalize(N) . normalize(I));\n    Oi = 1;\n}\n"},
    };
    return "Option \"searchpath\" \"shader\" [\"" +
           rd::test::shaderFolder("raydrive_displacement_point_params", kShaders) +
           ":&\"]\n";
}

// A square over the whole view, z = 3, seen head on (orthographic, 16 x 16 pixels, 4 x 4
// samples each) with `surface`, displaced by dpp_lift under `attributes`, its corners
// given `primvars`.
Rendered liftedSquare(const std::string& surface, const std::string& attributes,
                      const std::string& primvars) {
    return renderRib(shaderPath() +
                     "Format 16 16 1\nPixelSamples 4 4\n"
                     "Option \"render\" \"float pixelerror\" [1e-9]\n"
                     "Projection \"orthographic\"\nWorldBegin\n" +
                     attributes + "Surface \"" + surface +
                     "\"\nDisplacement \"dpp_lift\"\n"
                     "Polygon \"P\" [-1 -1 3  1 -1 3  1 1 3  -1 1 3] " +
                     primvars + "\nWorldEnd\n");
}

// The mean of channel 0 over the view's inner 12 x 12 pixels (a lifted edge may leave the
// view's border).
double inner(const Rendered& img) {
    return img.mean(0, 2, 2, 14, 14);
}

bool hasOption(const Rendered& img, const char* option) {
    return rd::buildOptions(img.stats.features).find(option) != std::string::npos;
}

const char* const kTrue = "Attribute \"displacementbound\" \"float sphere\" [1]\n";

}  // namespace

// "varying float h" 0 on the left edge, 1 on the right lifts the square along its normal
// by (x + 1) / 2: a slope of 1/2, so the moved surface faces the camera at 1 / sqrt(1.25)
// everywhere, as a bump (the moved surface's normal shades it) and truly displaced (the
// surface itself moves). Without the variable h is the shader's 0: a flat square, facing
// at 1. To 1e-4 (the ramp is linear, so each pixel's slope is exact up to its samples'
// finite differences; measured 0 to 1e-6).
TEST(DisplacementPointParams, VaryingHeightTiltsTheNormal) {
    const std::string ramp = "\"varying float h\" [0 1 1 0]";
    const double tilted = 1.0 / std::sqrt(1.25);
    Rendered flat = liftedSquare("dpp_facing", "", "");
    EXPECT_NEAR(inner(flat), 1.0, 1e-4);
    EXPECT_FALSE(hasOption(flat, "-DRSL_DISPLACEMENT_PRIMVARS"));
    Rendered bump = liftedSquare("dpp_facing", "", ramp);
    EXPECT_NEAR(inner(bump), tilted, 1e-4) << "bump mapped";
    EXPECT_TRUE(hasOption(bump, "-DRSL_DISPLACEMENT_PRIMVARS"));
    const auto names = bump.stats.features.names();
    EXPECT_NE(std::find(names.begin(), names.end(), "displacement_point_params"),
              names.end());
    Rendered moved = liftedSquare("dpp_facing", kTrue, ramp);
    EXPECT_NEAR(inner(moved), tilted, 1e-4) << "truly displaced";
    // "vertex" values on a PointsPolygons of two quads: the same slope
    Rendered mesh = renderRib(shaderPath() +
                              "Format 16 16 1\nPixelSamples 4 4\n"
                              "Option \"render\" \"float pixelerror\" [1e-9]\n"
                              "Projection \"orthographic\"\nWorldBegin\n"
                              "Surface \"dpp_facing\"\nDisplacement \"dpp_lift\"\n"
                              "PointsPolygons [4 4] [0 1 4 3  1 2 5 4] "
                              "\"P\" [-1 -1 3  0 -1 3  1 -1 3  -1 1 3  0 1 3  1 1 3] "
                              "\"vertex float h\" [0 0.5 1  0 0.5 1]\nWorldEnd\n");
    EXPECT_NEAR(inner(mesh), tilted, 1e-4);
}

// One variable reaches both shaders that have a parameter of its name: the surface
// shows h (its ramp, 0.5 on average over the inner pixels) times its facing ratio on the
// square that the displacement tilted by it (1 / sqrt(1.25)). A surface without the
// parameter leaves the build option to the displacement alone (above); a displacement
// without it gets none.
TEST(DisplacementPointParams, SurfaceAndDisplacementShareTheValues) {
    const std::string ramp = "\"varying float h\" [0 1 1 0]";
    const double tilted = 1.0 / std::sqrt(1.25);
    Rendered img = liftedSquare("dpp_value", kTrue, ramp);
    EXPECT_NEAR(inner(img), 0.5 * tilted, 1e-4);
    // the two rightmost columns, h 0.9375 on average
    EXPECT_NEAR(img.mean(0, 14, 2, 16, 14), 0.9375 * tilted, 1e-4);
    EXPECT_TRUE(hasOption(img, "-DRSL_DISPLACEMENT_PRIMVARS"));
    Rendered surfaceOnly = renderRib(shaderPath() +
                                     "Format 16 16 1\nPixelSamples 2 2\n"
                                     "Projection \"orthographic\"\nWorldBegin\n"
                                     "Surface \"dpp_value\"\nDisplacement \"bumpy\"\n"
                                     "Polygon \"P\" [-1 -1 3  1 -1 3  1 1 3  -1 1 3] " +
                                     ramp + "\nWorldEnd\n");
    EXPECT_TRUE(hasOption(surfaceOnly, "-DRSL_MAX_PARAM_PRIMVARS"));
    EXPECT_FALSE(hasOption(surfaceOnly, "-DRSL_DISPLACEMENT_PRIMVARS"));
}
