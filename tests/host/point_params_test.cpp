// point_params_test.cpp: primitive variables that give a shader parameter a value per
// point (varying, vertex, facevarying, uniform on several faces) rendered through the
// whole pipeline against the values they interpolate to: linear ramps across polygons,
// discontinuities between faces, bilinear corner values on a quadric (exact and diced),
// points moved to current space, hoisted uniform work that reads such a parameter, and
// no build option for scenes without them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "render/features.h"
#include "rib/reader.h"
#include "scene/rib_builder.h"
#include "render_harness.h"

using rd::test::Rendered;
using rd::test::renderRib;

namespace {

// Orthographic over [-1, 1]^2: pixel column i of W has its centre at x = -1 + (i + 0.5) 2 / W.
const int kSize = 16;
const std::string kCam = "Format 16 16 1\nPixelSamples 8 8\nOption \"render\" \"float pixelerror\" [1e-9]\nProjection \"orthographic\"\n";
double centre(int i) { return -1.0 + (i + 0.5) * 2.0 / kSize; }

// A folder of test shaders on the search path.
std::string shaders() {
    std::string dir = rd::test::scratchDir("raydrive_point_params");
    std::filesystem::create_directories(dir);
    std::ofstream(dir + "/pp_value.sl") << "surface pp_value(float Kd = 0.25; color tint = 1;) {\n"
                                           "    Oi = 1;\n    Ci = tint * Kd;\n}\n";
    // k is uniform: hoisted into the prepare kernel, unless Kd varies per point
    std::ofstream(dir + "/pp_hoist.sl") << "surface pp_hoist(float Kd = 0.5;) {\n"
                                           "    uniform float k = pow(Kd, 2) + 0.125;\n"
                                           "    Oi = 1;\n    Ci = k;\n}\n";
    std::ofstream(dir + "/pp_point.sl") << "surface pp_point(point Pref = point(100, 100, 100);) {\n"
                                           "    Oi = 1;\n    Ci = length(Pref - P);\n}\n";
    return "Option \"searchpath\" \"shader\" [\"" + dir + ":&\"]\n";
}

bool hasOption(const Rendered& img) {
    return rd::buildOptions(img.stats.features).find("-DRSL_MAX_PARAM_PRIMVARS") !=
           std::string::npos;
}

// Largest error of channel c against f(x) (y up: f(y)) at the pixel centres, over the
// columns [x0, x1) (rows) each averaged along its length: 16 x 64 samples, which keeps
// the sampling noise (the pixel's samples are random in it) under 1e-3.
template <class F>
double columnError(const Rendered& img, int c, F f, int x0 = 0, int x1 = kSize) {
    double e = 0;
    for (int x = x0; x < x1; ++x)
        e = std::max(e, std::fabs(img.mean(c, x, 0, x + 1, kSize) - f(centre(x))));
    return e;
}
template <class F>
double rowError(const Rendered& img, int c, F f) {
    double e = 0;
    for (int y = 0; y < kSize; ++y)
        e = std::max(e, std::fabs(img.mean(c, 0, y, kSize, y + 1) - f(-centre(y))));
    return e;
}

// A two-face mesh (left face x < 0, right face x > 0) with "facevarying float Kd"
// [0.2 0.2 0.2 0.2  0.6 1 1 0.6]: 0.2 on the left face (exact), 0.6 + 0.4 x on the right
// (3e-3); with "uniform float Kd" [2 5]: 2 and 5 (exact).
void expectPerFaceValues(const std::string& mesh) {
    const std::string world = shaders() + kCam + "WorldBegin\nSurface \"pp_value\"\n" + mesh;
    Rendered fv = renderRib(world + "\"facevarying float Kd\" [0.2 0.2 0.2 0.2  0.6 1 1 0.6]\n"
                                    "WorldEnd\n");
    EXPECT_LT(columnError(fv, 0, [](double) { return 0.2; }, 0, kSize / 2), 1e-5);
    EXPECT_LT(columnError(fv, 0, [](double x) { return 0.6 + 0.4 * x; }, kSize / 2, kSize), 3e-3);
    Rendered uni = renderRib(world + "\"uniform float Kd\" [2 5]\nWorldEnd\n");
    EXPECT_LT(columnError(uni, 0, [](double) { return 2.0; }, 0, kSize / 2), 1e-5);
    EXPECT_LT(columnError(uni, 0, [](double) { return 5.0; }, kSize / 2, kSize), 1e-5);
}

}  // namespace

// "varying float Kd" 0 at the left edge, 1 at the right, through matte lit head-on by a
// distant light (Ci = Kd exactly): every light mode of the shade kernel sees the value
// interpolated at the point. Pixels hold the ramp at their centres (a linear function's
// mean over the pixel), to 3e-3.
TEST(PointParams, VaryingFloatRampsAcrossAPolygon) {
    Rendered img = renderRib(kCam +
                             "WorldBegin\nLightSource \"distantlight\" 1 \"from\" [0 0 0] "
                             "\"to\" [0 0 1]\nSurface \"matte\" \"Ka\" 0 \"Kd\" 0.3\n"
                             "Polygon \"P\" [-1 -1 1  1 -1 1  1 1 1  -1 1 1] "
                             "\"varying float Kd\" [0 1 1 0]\nWorldEnd\n");
    EXPECT_LT(columnError(img, 0, [](double x) { return (x + 1) / 2; }), 3e-3);
    EXPECT_LT(columnError(img, 2, [](double x) { return (x + 1) / 2; }), 3e-3);
    EXPECT_TRUE(hasOption(img));
    const auto names = img.stats.features.names();
    EXPECT_NE(std::find(names.begin(), names.end(), "point_params"), names.end());
}

// "vertex color tint" on a PointsPolygons of two quads sharing an edge: a colour linear
// in x and y, so the triangulation does not matter; each channel to 3e-3.
TEST(PointParams, VertexColorOnPointsPolygons) {
    Rendered img = renderRib(shaders() + kCam +
                             "WorldBegin\nSurface \"pp_value\" \"Kd\" 1\n"
                             "PointsPolygons [4 4] [0 1 4 3  1 2 5 4] "
                             "\"P\" [-1 -1 1  0 -1 1  1 -1 1  -1 1 1  0 1 1  1 1 1] "
                             "\"vertex color tint\" [0 0 0.5  0.5 0 0.5  1 0 0.5  "
                             "0 1 0.5  0.5 1 0.5  1 1 0.5]\nWorldEnd\n");
    EXPECT_LT(columnError(img, 0, [](double x) { return (x + 1) / 2; }), 3e-3);
    EXPECT_LT(rowError(img, 1, [](double y) { return (y + 1) / 2; }), 3e-3);
    EXPECT_LT(columnError(img, 2, [](double) { return 0.5; }), 1e-5);
}

// facevarying: the two faces share their middle vertices but not their values there
// (left face 0.2 everywhere, right face 0.6 at x = 0 up to 1.0 at x = 1); uniform: one
// value per face (exact, 1e-5); the ramp to 3e-3.
TEST(PointParams, FaceVaryingAndUniformPerFace) {
    const std::string mesh = "PointsPolygons [4 4] [0 1 4 3  1 2 5 4] "
                             "\"P\" [-1 -1 1  0 -1 1  1 -1 1  -1 1 1  0 1 1  1 1 1] ";
    expectPerFaceValues(mesh);
}

// The standard Cs and st per face and per face-vertex on a PointsPolygons (before
// session 30 only per-vertex ones were read and these rendered white, st (0, 0)):
// "uniform color Cs" red and green faces, exact; "facevarying float[2] st" read by the
// shader as s, the left face's 0.2 and the right face's ramp, as for a parameter.
TEST(PointParams, StandardValuesPerFaceOnPointsPolygons) {
    const std::string mesh =
        "PointsPolygons [4 4] [0 1 4 3  1 2 5 4] "
        "\"P\" [-1 -1 1  0 -1 1  1 -1 1  -1 1 1  0 1 1  1 1 1] ";
    Rendered cs = renderRib(kCam + "WorldBegin\nSurface \"constant\"\n" + mesh +
                            "\"uniform color Cs\" [1 0 0  0 1 0]\nWorldEnd\n");
    EXPECT_LT(columnError(
                  cs, 0, [](double) { return 1.0; }, 0, kSize / 2),
              1e-5);
    EXPECT_LT(columnError(
                  cs, 1, [](double) { return 0.0; }, 0, kSize / 2),
              1e-5);
    EXPECT_LT(columnError(
                  cs, 0, [](double) { return 0.0; }, kSize / 2, kSize),
              1e-5);
    EXPECT_LT(columnError(
                  cs, 1, [](double) { return 1.0; }, kSize / 2, kSize),
              1e-5);
    std::ofstream(rd::test::scratchDir("raydrive_point_params") + "/pp_s.sl")
        << "surface pp_s() {\n    Oi = 1;\n    Ci = s;\n}\n";
    Rendered st = renderRib(shaders() + kCam + "WorldBegin\nSurface \"pp_s\"\n" + mesh +
                            "\"facevarying float[2] st\" [0.2 0  0.2 0  0.2 0  0.2 0  "
                            "0.6 0  1 0  1 0  0.6 0]\nWorldEnd\n");
    EXPECT_LT(columnError(
                  st, 0, [](double) { return 0.2; }, 0, kSize / 2),
              1e-5);
    EXPECT_LT(columnError(
                  st, 0, [](double x) { return 0.6 + 0.4 * x; }, kSize / 2, kSize),
              3e-3);
}

// General polygons (triangulated by ear clipping, vertices shared): a square with a
// square hole, "varying float Kd" = (x + 1) / 2 at its 8 points, is that ramp on the
// ring (the hole shows nothing); PointsGeneralPolygons with one value per polygon
// ("uniform") and per polygon corner ("facevarying").
TEST(PointParams, GeneralPolygons) {
    Rendered ring = renderRib(shaders() + kCam + "WorldBegin\nSurface \"pp_value\"\n"
                              "GeneralPolygon [4 4] \"P\" [-1 -1 1  1 -1 1  1 1 1  -1 1 1  "
                              "-0.5 -0.5 1  -0.5 0.5 1  0.5 0.5 1  0.5 -0.5 1] "
                              "\"varying float Kd\" [0 1 1 0  0.25 0.25 0.75 0.75]\nWorldEnd\n");
    double e = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const bool hole = std::fabs(centre(x)) < 0.5 && std::fabs(centre(y)) < 0.5;
            const bool ringOnly = std::fabs(centre(x)) > 0.5 || std::fabs(centre(y)) > 0.5;
            if (hole) {
                EXPECT_EQ(ring.at(x, y).a, 0.0f) << x << " " << y;
            }
            if (ringOnly && std::fabs(std::fabs(centre(x)) - 0.5) > 0.1 &&
                std::fabs(std::fabs(centre(y)) - 0.5) > 0.1)
                e = std::max(e, std::fabs(double(ring.at(x, y).r) - (centre(x) + 1) / 2));
        }
    EXPECT_LT(e, 1.5e-2) << "single pixels (64 samples each)";
    const std::string mesh = "PointsGeneralPolygons [1 1] [4 4] [0 1 4 3  1 2 5 4] "
                             "\"P\" [-1 -1 1  0 -1 1  1 -1 1  -1 1 1  0 1 1  1 1 1] ";
    expectPerFaceValues(mesh);
}

// Patches: a bilinear Patch's 4 varying values are bilinear in (u, v) (Kd = u = (x +
// 1) / 2, to 3e-3); a bicubic (Bezier) Patch's 16 vertex values go through its basis:
// 0 0 1 1 along u is 3u^2 - 2u^3 (compared with its mean over each column, to 4e-3:
// linear between the dicing's vertices);
// a bilinear PatchMesh of 2 x 1 sub-patches has one uniform value each (exact).
TEST(PointParams, Patches) {
    const std::string world = shaders() + kCam + "WorldBegin\nSurface \"pp_value\"\n";
    Rendered bilinear = renderRib(world + "Patch \"bilinear\" \"P\" [-1 -1 1  1 -1 1  -1 1 1  1 1 1] "
                                          "\"varying float Kd\" [0 1 0 1]\nWorldEnd\n");
    EXPECT_LT(columnError(bilinear, 0, [](double x) { return (x + 1) / 2; }), 3e-3);
    std::string p, kd;
    for (int b = 0; b < 4; ++b)
        for (int a = 0; a < 4; ++a) {
            p += std::to_string(-1 + 2 * a / 3.0) + " " + std::to_string(-1 + 2 * b / 3.0) + " 1 ";
            kd += a < 2 ? "0 " : "1 ";
        }
    Rendered bicubic = renderRib(world + "Patch \"bicubic\" \"P\" [" + p + "] \"vertex float Kd\" [" +
                                 kd + "]\nWorldEnd\n");
    auto smoothMean = [](double x) {  // the column's mean of 3u^2 - 2u^3, u = (x + 1) / 2
        auto F = [](double u) { return u * u * u - u * u * u * u / 2; };
        const double u = (x + 1) / 2, h = 0.5 / kSize;
        return (F(u + h) - F(u - h)) / (2 * h);
    };
    EXPECT_LT(columnError(bicubic, 0, smoothMean), 4e-3);
    Rendered mesh = renderRib(world + "PatchMesh \"bilinear\" 3 \"nonperiodic\" 2 \"nonperiodic\" "
                                      "\"P\" [-1 -1 1  0 -1 1  1 -1 1  -1 1 1  0 1 1  1 1 1] "
                                      "\"uniform float Kd\" [2 5]\nWorldEnd\n");
    EXPECT_LT(columnError(mesh, 0, [](double) { return 2.0; }, 0, kSize / 2), 1e-5);
    EXPECT_LT(columnError(mesh, 0, [](double) { return 5.0; }, kSize / 2, kSize), 1e-5);
}

// A bicubic PatchMesh's vertex values are one a control point, through each sub-patch's
// basis over the same 4 x 4 points as its positions. A b-spline mesh of 6 x 4 evenly
// spaced points covers [-1, 1]^2 (3 sub-patches across), and values linear in the
// points' x and y, (x + 1) / 4 + (y + 1) / 4, are that function of the surface point:
// every pixel to 5e-3. A Bezier mesh of 7 columns (ustep 3: 2 sub-patches sharing
// column 3) with columns' values [0 0 0 0 1 1 1] is 0 left of the middle and
// 1 - (1 - u)^3 right of it (u = x there), by column means to 4e-3: a sub-patch that
// took its values from columns 1-4 (no step) fails it.
TEST(PointParams, BicubicPatchMeshVertexValues) {
    const std::string world = shaders() + kCam + "WorldBegin\nSurface \"pp_value\"\n";
    std::string p, kd;
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 6; ++i) {
            const double x = -5.0 / 3 + i * 2.0 / 3, y = -3.0 + 2 * j;
            p += std::to_string(x) + " " + std::to_string(y) + " 1  ";
            kd += std::to_string((x + 1) / 4 + (y + 1) / 4) + " ";
        }
    Rendered bspline = renderRib(world + "Basis \"b-spline\" 1 \"b-spline\" 1\n"
                                 "PatchMesh \"bicubic\" 6 \"nonperiodic\" 4 \"nonperiodic\" "
                                 "\"P\" [" + p + "] \"vertex float Kd\" [" + kd + "]\nWorldEnd\n");
    double worst = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const double want = (centre(x) + 1) / 4 + (-centre(y) + 1) / 4;
            worst = std::max(worst, std::fabs(bspline.mean(0, x, y, x + 1, y + 1) - want));
        }
    EXPECT_LT(worst, 5e-3);
    p.clear(), kd.clear();
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 7; ++i) {
            p += std::to_string(-1 + i / 3.0) + " " + std::to_string(-1 + 2 * j / 3.0) + " 1  ";
            kd += i < 4 ? "0 " : "1 ";
        }
    Rendered bezier = renderRib(world + "PatchMesh \"bicubic\" 7 \"nonperiodic\" 4 \"nonperiodic\" "
                                "\"P\" [" + p + "] \"vertex float Kd\" [" + kd + "]\nWorldEnd\n");
    auto rightHalf = [](double x) {  // the column's mean of 1 - (1 - u)^3, u = x
        if (x < 0) return 0.0;
        auto F = [](double u) { return u + std::pow(1 - u, 4) / 4; };
        const double h = 1.0 / kSize;
        return (F(x + h) - F(x - h)) / (2 * h);
    };
    EXPECT_LT(columnError(bezier, 0, rightHalf), 4e-3);
}

// Points: each disc has its point's value ("varying float Kd" [0.3 0.9]) all over;
// pixels the discs cover whole, exact.
TEST(PointParams, PointsHaveTheirPointsValue) {
    Rendered img = renderRib(shaders() + kCam + "WorldBegin\nSurface \"pp_value\"\n"
                             "Points \"P\" [-0.5 0 1  0.5 0 1] \"constantwidth\" [0.5] "
                             "\"varying float Kd\" [0.3 0.9]\nWorldEnd\n");
    for (int y : {7, 8}) {
        EXPECT_NEAR(img.at(4, y).r, 0.3, 1e-5);
        EXPECT_NEAR(img.at(11, y).r, 0.9, 1e-5);
    }
}

// SubdivisionMesh: a flat 3 x 3 cage over [-1, 1]^2 (boundary interpolated) with a
// value affine in x at its vertices: "vertex" (to the limit, which reproduces affine
// functions) and "varying" (refined linearly) both give (x + 1) / 2, to 3e-3;
// "uniform" [1 2 3 4] one value per base face (the four quadrants), exact.
TEST(PointParams, SubdivisionMesh) {
    const std::string cage =
        "SubdivisionMesh \"catmull-clark\" [4 4 4 4] [0 1 4 3  1 2 5 4  3 4 7 6  4 5 8 7] "
        "[\"interpolateboundary\"] [0 0] [] [] "
        "\"P\" [-1 -1 1  0 -1 1  1 -1 1  -1 0 1  0 0 1  1 0 1  -1 1 1  0 1 1  1 1 1] ";
    const std::string ramp = "[0 0.5 1  0 0.5 1  0 0.5 1]";
    for (const char* storage : {"vertex", "varying"}) {
        Rendered img = renderRib(shaders() + kCam + "WorldBegin\nSurface \"pp_value\"\n" + cage +
                                 "\"" + storage + " float Kd\" " + ramp + "\nWorldEnd\n");
        EXPECT_LT(columnError(img, 0, [](double x) { return (x + 1) / 2; }), 3e-3) << storage;
    }
    // a bump (1 at the middle vertex, 0 around) tells them apart: the limit there is
    // 16/36 (Catmull-Clark's limit stencil at a valence-4 vertex), linear refinement
    // keeps 1; the 4 middle pixels' mean, against 4/9 (to 0.03, its curvature over them)
    // and the tent's mean (1 - 1/16)^2 (to 0.01)
    const std::string bump = "[0 0 0  0 1 0  0 0 0]";
    Rendered vb = renderRib(shaders() + kCam + "WorldBegin\nSurface \"pp_value\"\n" + cage +
                            "\"vertex float Kd\" " + bump + "\nWorldEnd\n");
    EXPECT_NEAR(vb.mean(0, 7, 7, 9, 9), 4.0 / 9.0, 0.03);
    Rendered lb = renderRib(shaders() + kCam + "WorldBegin\nSurface \"pp_value\"\n" + cage +
                            "\"varying float Kd\" " + bump + "\nWorldEnd\n");
    EXPECT_NEAR(lb.mean(0, 7, 7, 9, 9), (1 - 1.0 / 16) * (1 - 1.0 / 16), 0.01);
    // facevarying values (an OpenSubdiv face-varying channel, split at the seam x = 0)
    // and per face, on a two-face cage, as on polygons; the facevarying ones beside a
    // vertex and a varying parameter (their refined values in the order SubdivInput
    // lists them) and a facevarying colour
    expectPerFaceValues("SubdivisionMesh \"catmull-clark\" [4 4] [0 1 4 3  1 2 5 4] "
                        "[\"interpolateboundary\"] [0 0] [] [] "
                        "\"P\" [-1 -1 1  0 -1 1  1 -1 1  -1 1 1  0 1 1  1 1 1] ");
    Rendered mixed = renderRib(
        shaders() + kCam + "WorldBegin\nSurface \"pp_value\"\n" + cage +
        "\"vertex color tint\" [1 1 1  1 1 1  1 1 1  1 1 1  1 1 1  1 1 1  1 1 1  1 1 1  1 1 1] "
        "\"facevarying float Kd\" [0 0.2 0.2 0  0.6 1 1 0.6  0 0.2 0.2 0  0.6 1 1 0.6] "
        "\"varying color Os\" [1 1 1  1 1 1  1 1 1  1 1 1  1 1 1  1 1 1  1 1 1  1 1 1  1 1 1] "
        "\"facevarying color Cs\" [1 0 0  1 0 0  1 0 0  1 0 0  0 0 1  0 0 1  0 0 1  0 0 1  "
        "1 0 0  1 0 0  1 0 0  1 0 0  0 0 1  0 0 1  0 0 1  0 0 1]\nWorldEnd\n");
    EXPECT_LT(columnError(mixed, 0, [](double x) { return 0.2 * (x + 1); }, 0, kSize / 2), 3e-3);
    EXPECT_LT(columnError(mixed, 0, [](double x) { return 0.6 + 0.4 * x; }, kSize / 2, kSize),
              3e-3);
    // the facevarying colour itself, through the constant shader: red left, blue right
    Rendered colour = renderRib(
        kCam + "WorldBegin\nSurface \"constant\"\n" + cage +
        "\"facevarying color Cs\" [1 0 0  1 0 0  1 0 0  1 0 0  0 0 1  0 0 1  0 0 1  0 0 1  "
        "1 0 0  1 0 0  1 0 0  1 0 0  0 0 1  0 0 1  0 0 1  0 0 1]\nWorldEnd\n");
    EXPECT_LT(columnError(colour, 0, [](double) { return 1.0; }, 0, kSize / 2), 1e-5);
    EXPECT_LT(columnError(colour, 2, [](double) { return 0.0; }, 0, kSize / 2), 1e-5);
    EXPECT_LT(columnError(colour, 0, [](double) { return 0.0; }, kSize / 2, kSize), 1e-5);
    EXPECT_LT(columnError(colour, 2, [](double) { return 1.0; }, kSize / 2, kSize), 1e-5);
    Rendered uni = renderRib(shaders() + kCam + "WorldBegin\nSurface \"pp_value\"\n" + cage +
                             "\"uniform float Kd\" [1 2 3 4]\nWorldEnd\n");
    EXPECT_NEAR(uni.at(4, 12).r, 1.0, 1e-5);
    EXPECT_NEAR(uni.at(12, 12).r, 2.0, 1e-5);
    EXPECT_NEAR(uni.at(4, 4).r, 3.0, 1e-5);
    EXPECT_NEAR(uni.at(12, 4).r, 4.0, 1e-5);
}

// Curves: a linear curve across the view (x from -1.5 to 1.5 along 3 vertices, width 1)
// with "varying float Kd" [-0.25 0.5 1.25] is (x + 1) / 2 along it, to 3e-3 (column
// means of the covered rows 4 to 11); "uniform" one value per curve (two), exact.
TEST(PointParams, Curves) {
    Rendered img = renderRib(shaders() + kCam + "WorldBegin\nSurface \"pp_value\"\n"
                             "Curves \"linear\" [3] \"nonperiodic\" \"P\" [-1.5 0 1  0 0 1  1.5 0 1] "
                             "\"constantwidth\" [1] \"varying float Kd\" [-0.25 0.5 1.25]\nWorldEnd\n");
    double e = 0;
    for (int x = 0; x < kSize; ++x)
        e = std::max(e, std::fabs(img.mean(0, x, 4, x + 1, 12) - (centre(x) + 1) / 2));
    EXPECT_LT(e, 3e-3);
    Rendered uni = renderRib(shaders() + kCam + "WorldBegin\nSurface \"pp_value\"\n"
                             "Curves \"linear\" [2 2] \"nonperiodic\" "
                             "\"P\" [-1.5 -0.5 1  1.5 -0.5 1  -1.5 0.5 1  1.5 0.5 1] "
                             "\"constantwidth\" [0.5] \"uniform float Kd\" [2 5]\nWorldEnd\n");
    EXPECT_NEAR(uni.at(8, 12).r, 2.0, 1e-5);
    EXPECT_NEAR(uni.at(8, 3).r, 5.0, 1e-5);
}

// A deforming mesh (MotionBegin around two keys of a polygon, still here) is shaded
// with its first key's values: the ramp, to 3e-3.
TEST(PointParams, DeformingMeshKeepsItsValues) {
    const std::string key = "Polygon \"P\" [-1 -1 1  1 -1 1  1 1 1  -1 1 1] "
                            "\"varying float Kd\" [0 1 1 0]\n";
    Rendered img = renderRib(shaders() + kCam + "Shutter 0 1\nWorldBegin\nSurface \"pp_value\"\n"
                             "MotionBegin [0 1]\n" + key + key + "MotionEnd\nWorldEnd\n");
    EXPECT_LT(columnError(img, 0, [](double x) { return (x + 1) / 2; }), 3e-3);
}

// NuPatch: varying values sit on the corners of the knot spans. Order 2 (linear) in u
// with knots 0 0 1 3 3 puts x = -1, 0, 1 at u = 0, 1, 3, so values 0, 0.5, 1 there are
// (x + 1) / 2 again, to 3e-3, only if each span is found by its knots.
TEST(PointParams, NuPatchKnotSpans) {
    Rendered img = renderRib(shaders() + kCam + "WorldBegin\nSurface \"pp_value\"\n"
                             "NuPatch 3 2 [0 0 1 3 3] 0 3 2 2 [0 0 1 1] 0 1 "
                             "\"P\" [-1 -1 1  0 -1 1  1 -1 1  -1 1 1  0 1 1  1 1 1] "
                             "\"varying float Kd\" [0 0.5 1  0 0.5 1]\nWorldEnd\n");
    EXPECT_LT(columnError(img, 0, [](double x) { return (x + 1) / 2; }), 3e-3);
}

// NuPatch vertex values: one per control point, through the surface's own basis. A
// quadratic Bezier patch (order 3, knots 0 0 0 1 1 1) over evenly spaced control points
// has x = 2u - 1: a ramp 0, 0.5, 1 across its columns of control points is (x + 1) / 2
// (to 3e-3); a bump (1 at the middle control point) is B(u) B(v), B(t) = 2t(1 - t), so
// 1/4 at the middle (the 2x2 middle pixels' mean to 0.02); with weight 2 there (Pw,
// rational), 0.5 / 1.25 = 0.4 (the weights divide the values as they do the points).
TEST(PointParams, NuPatchVertexValuesFollowItsBasis) {
    auto patch = [](bool rational) {
        std::string p = rational ? "\"Pw\" [" : "\"P\" [";
        for (int j = 0; j < 3; ++j)
            for (int i = 0; i < 3; ++i) {
                const double w = rational && i == 1 && j == 1 ? 2.0 : 1.0;
                p += std::to_string((i - 1) * w) + " " + std::to_string((j - 1) * w) + " " +
                     std::to_string(w) + (rational ? " " + std::to_string(w) : "") + "  ";
            }
        return "NuPatch 3 3 [0 0 0 1 1 1] 0 1 3 3 [0 0 0 1 1 1] 0 1 " + p + "] ";
    };
    const std::string world = shaders() + kCam + "WorldBegin\nSurface \"pp_value\"\n";
    Rendered ramp = renderRib(world + patch(false) +
                              "\"vertex float Kd\" [0 0.5 1  0 0.5 1  0 0.5 1]\nWorldEnd\n");
    EXPECT_LT(columnError(ramp, 0, [](double x) { return (x + 1) / 2; }), 3e-3);
    const std::string bump = "\"vertex float Kd\" [0 0 0  0 1 0  0 0 0]\nWorldEnd\n";
    Rendered plain = renderRib(world + patch(false) + bump);
    EXPECT_NEAR(plain.mean(0, 7, 7, 9, 9), 0.25, 0.02);
    Rendered weighted = renderRib(world + patch(true) + bump);
    EXPECT_NEAR(weighted.mean(0, 7, 7, 9, 9), 0.4, 0.02);
}

// Per-point values inside ObjectBegin reach each instance's surface. A square's
// "varying float Kd" ramp [0 1 1 0], shared by two instances (one prototype): Kd = x + 1
// on the left one, under its Surface, and 2 x (tint 2) on the right one, under another;
// each to 3e-3 by column. A "varying point Pref" equal to P inside an object is P
// wherever an instance puts it (those instances are copies): 0 everywhere, to 1e-4. A
// sphere's [0 0 1 1] in an object is v on its instance, as in VaryingOnASphere.
TEST(PointParams, InsideObjectBegin) {
    const std::string world = shaders() + kCam + "WorldBegin\n";
    Rendered ramp = renderRib(world + "ObjectBegin \"sq\"\nPolygon \"P\" [-0.5 -1 1  0.5 -1 1  "
                              "0.5 1 1  -0.5 1 1] \"varying float Kd\" [0 1 1 0]\nObjectEnd\n"
                              "AttributeBegin\nSurface \"pp_value\"\nTranslate -0.5 0 0\n"
                              "ObjectInstance \"sq\"\nAttributeEnd\n"
                              "AttributeBegin\nSurface \"pp_value\" \"color tint\" [2 2 2]\n"
                              "Translate 0.5 0 0\nObjectInstance \"sq\"\nAttributeEnd\nWorldEnd\n");
    EXPECT_LT(columnError(ramp, 0, [](double x) { return x + 1; }, 0, kSize / 2), 3e-3);
    EXPECT_LT(columnError(ramp, 0, [](double x) { return 2 * x; }, kSize / 2, kSize), 3e-3);
    EXPECT_TRUE(hasOption(ramp));
    Rendered point = renderRib(world + "ObjectBegin \"sq\"\nScale 0.5 1 1\n"
                               "Polygon \"P\" [-1 -1 0  1 -1 0  1 1 0  -1 1 0] "
                               "\"varying point Pref\" [-1 -1 0  1 -1 0  1 1 0  -1 1 0]\n"
                               "ObjectEnd\nSurface \"pp_point\"\nTranslate 0 0 2\n"
                               "AttributeBegin\nTranslate -0.5 0 0\nRotate 10 0 1 0\n"
                               "ObjectInstance \"sq\"\nAttributeEnd\n"
                               "AttributeBegin\nTranslate 0.5 0 0\nObjectInstance \"sq\"\n"
                               "AttributeEnd\nWorldEnd\n");
    EXPECT_LT(columnError(point, 0, [](double) { return 0.0; }), 1e-4);
    Rendered ball = renderRib(world + "Surface \"pp_value\"\nObjectBegin \"ball\"\n"
                              "Rotate -90 1 0 0\nSphere 1 -1 1 360 \"varying float Kd\" [0 0 1 1]\n"
                              "ObjectEnd\nTranslate 0 0 5\nObjectInstance \"ball\"\nWorldEnd\n");
    for (int y = 2; y < kSize - 2; ++y)
        EXPECT_NEAR(ball.mean(0, kSize / 2 - 1, y, kSize / 2 + 1, y + 1),
                    std::asin(-centre(y)) / M_PI + 0.5, 0.01)
            << "row " << y;
}

// A uniform declaration reading a per-point parameter is computed at the point, not
// once per instance: Ci = Kd^2 + 0.125 along the ramp (Kd = x; a pixel's mean of x^2 is
// its centre's plus (1/16)^2 / 3), to 3e-3. The same shader on a polygon
// without the variable still hoists it (its default: 0.375).
TEST(PointParams, HoistedWorkFollowsThePerPointParameter) {
    Rendered img = renderRib(shaders() + kCam + "WorldBegin\nSurface \"pp_hoist\"\n"
                             "Polygon \"P\" [-1 -1 1  0 -1 1  0 1 1  -1 1 1]\n"
                             "Polygon \"P\" [0 -1 1  1 -1 1  1 1 1  0 1 1] "
                             "\"varying float Kd\" [0 1 1 0]\nWorldEnd\n");
    EXPECT_LT(columnError(img, 0, [](double) { return 0.375; }, 0, kSize / 2), 1e-5);
    EXPECT_LT(columnError(img, 0, [](double x) { return x * x + 0.125 + 1.0 / (3 * 16 * 16); }, kSize / 2, kSize), 3e-3);
    EXPECT_EQ(img.stats.kernels.count("rd_prepare_uniforms"), 1u);
}

// A varying point reaches the shader in current space: "Pref" given equal to "P" under
// a rotation and translation is P at every shading point (|Pref - P| under 1e-4).
TEST(PointParams, PointsAreInCurrentSpace) {
    Rendered img = renderRib(shaders() + kCam + "WorldBegin\nSurface \"pp_point\"\n"
                             "Translate 0.25 -0.125 2\nRotate 30 0 0 1\nScale 0.5 0.5 0.5\n"
                             "Polygon \"P\" [-3 -3 0  3 -3 0  3 3 0  -3 3 0] "
                             "\"varying point Pref\" [-3 -3 0  3 -3 0  3 3 0  -3 3 0]\nWorldEnd\n");
    EXPECT_LT(columnError(img, 0, [](double) { return 0.0; }), 1e-4);
}

// A quadric's varying values are at its (u, v) corners: "varying float Kd" [0 0 1 1] is
// v, which on a full sphere is (asin(z / r) + pi/2) / pi. The sphere's z axis is turned
// to the screen's y (Rotate -90 about x), so down the middle column Kd = asin(y)/pi +
// 1/2; exact and diced (exactquadrics 0) alike, to 0.01 (pixels over 1/8 of the radius).
// The polygon behind it, with no such variable, keeps the shader's default.
TEST(PointParams, VaryingOnASphere) {
    for (int exact : {1, 0}) {
        Rendered img = renderRib(shaders() + "Option \"render\" \"int exactquadrics\" [" +
                                 std::to_string(exact) + "]\n" + kCam +
                                 "WorldBegin\nSurface \"pp_value\"\n"
                                 "Polygon \"P\" [-2 -2 9  2 -2 9  2 2 9  -2 2 9]\nTranslate 0 0 5\n"
                                 "Rotate -90 1 0 0\nSphere 1 -1 1 360 \"varying float Kd\" [0 0 1 1]\n"
                                 "WorldEnd\n");
        EXPECT_NEAR(img.at(0, 0).r, 0.25, 1e-6) << "a polygon without them, behind";
        for (int y = 2; y < kSize - 2; ++y) {
            const double sy = -centre(y);
            const double want = std::asin(sy) / M_PI + 0.5;
            EXPECT_NEAR(img.mean(0, kSize / 2 - 1, y, kSize / 2 + 1, y + 1), want, 0.01)
                << "row " << y << " exact " << exact;
        }
        EXPECT_TRUE(hasOption(img));
    }
}

// The other quadrics the same way: on a cylinder turned like the sphere above,
// [0 0 1 1] is v = (y + 1) / 2 in every row, exact and diced, to 3e-3.
TEST(PointParams, VaryingOnACylinder) {
    for (int exact : {1, 0}) {
        Rendered img = renderRib(shaders() + "Option \"render\" \"int exactquadrics\" [" +
                                 std::to_string(exact) + "]\n" + kCam +
                                 "WorldBegin\nSurface \"pp_value\"\nTranslate 0 0 5\n"
                                 "Rotate -90 1 0 0\nCylinder 1 -1 1 360 \"varying float Kd\" [0 0 1 1]\n"
                                 "WorldEnd\n");
        EXPECT_LT(rowError(img, 0, [](double y) { return (y + 1) / 2; }), 3e-3) << "exact " << exact;
    }
}

// Only scenes that feed parameters per point get the code: none given, one naming no
// parameter of the shader, or a single value (a constant) leaves the build option out.
TEST(PointParams, NoOptionWithoutThem) {
    Rendered none = renderRib(shaders() + kCam + "WorldBegin\nSurface \"pp_value\"\n"
                              "Polygon \"P\" [-1 -1 1  1 -1 1  1 1 1  -1 1 1]\nWorldEnd\n");
    EXPECT_FALSE(hasOption(none));
    EXPECT_NEAR(none.at(8, 8).r, 0.25, 1e-6);
    Rendered other = renderRib(shaders() + kCam + "WorldBegin\nSurface \"pp_value\"\n"
                               "Polygon \"P\" [-1 -1 1  1 -1 1  1 1 1  -1 1 1] "
                               "\"varying float notaparam\" [0 1 1 0]\nWorldEnd\n");
    EXPECT_FALSE(hasOption(other));
    EXPECT_NEAR(other.at(8, 8).r, 0.25, 1e-6);
    // one value of any class is the primitive's constant (as the reader accepts it)
    Rendered one = renderRib(shaders() + kCam + "WorldBegin\nSurface \"pp_value\"\n"
                             "Polygon \"P\" [-1 -1 1  1 -1 1  1 1 1  -1 1 1] "
                             "\"varying float Kd\" [0.75]\nWorldEnd\n");
    EXPECT_FALSE(hasOption(one));
    EXPECT_NEAR(one.at(8, 8).r, 0.75, 1e-6);
}

// Bad input keeps its file:line: a wrong number of values is the reader's error (for a
// mesh's facevarying and uniform classes and a quadric's 4 corners); a variable whose
// type does not fit the parameter is a warning at the Surface call and is ignored.
TEST(PointParams, BadInputIsReportedWithFileAndLine) {
    std::ostringstream out;
    rib::Diagnostics diag(&out);
    rd::RibBuilder builder(diag, "t.rib");
    rib::readString("WorldBegin\nSurface \"pp_value\"\n"
                    "PointsPolygons [4 4] [0 1 4 3  1 2 5 4] "
                    "\"P\" [-1 -1 1  0 -1 1  1 -1 1  -1 1 1  0 1 1  1 1 1] "
                    "\"facevarying float Kd\" [1 2 3]\n"
                    "PointsPolygons [4 4] [0 1 4 3  1 2 5 4] "
                    "\"P\" [-1 -1 1  0 -1 1  1 -1 1  -1 1 1  0 1 1  1 1 1] "
                    "\"uniform float Kd\" [1 2 3]\n"
                    "Sphere 1 -1 1 360 \"varying float Kd\" [0 1]\nWorldEnd\n",
                    "t.rib", builder, diag);
    const std::string text = out.str();
    EXPECT_NE(text.find("t.rib:3: error: PointsPolygons: facevarying \"Kd\" has 3 values, needs 8"),
              std::string::npos) << text;
    EXPECT_NE(text.find("t.rib:4: error: PointsPolygons: uniform \"Kd\" has 3 values, needs 2"),
              std::string::npos) << text;
    EXPECT_NE(text.find("t.rib:5: error: Sphere: varying \"Kd\" has 2 values, needs 4"),
              std::string::npos) << text;

    ::testing::internal::CaptureStderr();
    Rendered img = renderRib(shaders() + kCam + "WorldBegin\nSurface \"pp_value\"\n"
                             "Polygon \"P\" [-1 -1 1  1 -1 1  1 1 1  -1 1 1] "
                             "\"varying color Kd\" [0 0 0  1 1 1  1 1 1  0 0 0]\nWorldEnd\n");
    const std::string err = ::testing::internal::GetCapturedStderr();
    EXPECT_NE(err.find("test.rib:7: warning: primitive variable \"Kd\" of 3 float(s) per point "
                       "does not fit parameter \"Kd\" (a float) of shader \"pp_value\"; ignored"),
              std::string::npos) << err;
    EXPECT_NEAR(img.at(8, 8).r, 0.25, 1e-6) << "the parameter keeps its value";
}
