// derivatives_test.cpp: shader derivatives (Du, Dv, Deriv, area, calculatenormal,
// filterstep) as finite differences over a shading point's neighbours one ray footprint
// away, and Displacement shaders as bump maps, each against its closed form.
// Footprints: orthographic 2/W per pixel; perspective (fov 90) 2/W per unit of distance.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "render_harness.h"

using rd::test::Rendered;
using rd::test::renderRib;

namespace {

const double kPi = 3.14159265358979;

// Writes the test shaders into a folder on the search path; returns the RIB option.
std::string shaderPath() {
    std::string dir = rd::test::scratchDir("raydrive_derivative_shaders");
    std::filesystem::create_directories(dir);
    // r, g: the change of s over one footprint along dPdu and dPdv (the film takes no
    // negative colours); b: area(P)
    std::ofstream(dir + "/dstep.sl") << "surface dstep() {\n"
                                        "    Ci = color(abs(Du(s) * du), abs(Dv(s) * dv), area(P));\n"
                                        "    Oi = 1;\n}\n";
    std::ofstream(dir + "/dnormal.sl")
        << "surface dnormal() {\n"
           "    normal n = normalize(calculatenormal(P));\n"
           "    Ci = color(n . normalize(N), abs(Deriv(s * s, s) - 2 * s), 0);\n"
           "    Oi = 1;\n}\n";
    std::ofstream(dir + "/dfilter.sl") << "surface dfilter(float edge = 0.5) {\n"
                                          "    Ci = filterstep(edge, s);\n    Oi = 1;\n}\n";
    // a sinusoidal bump across s: height amp sin(2 pi freq s) along N
    std::ofstream(dir + "/wave.sl") << "displacement wave(float amp = 0.1, freq = 1) {\n"
                                       "    P += amp * sin(2 * PI * freq * s) * normalize(N);\n"
                                       "    N = calculatenormal(P);\n}\n";
    // the same bump that moves P only: the renderer takes the moved surface's normal
    std::ofstream(dir + "/waveP.sl") << "displacement waveP(float amp = 0.1, freq = 1) {\n"
                                        "    P += amp * sin(2 * PI * freq * s) * normalize(N);\n}\n";
    return "Option \"searchpath\" \"shader\" [\"" + dir + ":&\"]\n";
}

// A square patch filling an orthographic view, s = (x + 1) / 2 across it.
Rendered orthoSquare(int size, const std::string& shaders) {
    return renderRib(shaderPath() + "Format " + std::to_string(size) + " " +
                     std::to_string(size) +
                     " 1\nPixelSamples 1 1\nProjection \"orthographic\"\nWorldBegin\n"
                     "LightSource \"distantlight\" 1 \"from\" [0 0 -1] \"to\" [0 0 0]\n"
                     "Translate 0 0 5\n" + shaders +
                     "\nPatch \"bilinear\" \"P\" [-1 1 0  1 1 0  -1 -1 0  1 -1 0]\nWorldEnd\n");
}

}  // namespace

// Orthographic: the footprint is a pixel, w = 2/16. s changes by 0.5 per unit of x, so
// over one footprint its change has length |grad s| w = 0.0625 whichever way the
// triangles cut the patch (dPdu, dPdv are an orthogonal frame); area(P) = w^2.
TEST(Derivatives, FootprintStepsAndAreaOrthographic) {
    Rendered img = orthoSquare(16, "Surface \"dstep\"");
    double worst = 0, worstArea = 0;
    for (int y = 1; y < 15; ++y)
        for (int x = 1; x < 15; ++x) {
            const auto& p = img.at(x, y);
            worst = std::fmax(worst, std::fabs(std::hypot(p.r, p.g) - 0.0625));
            worstArea = std::fmax(worstArea, std::fabs(p.b - 0.015625));
        }
    EXPECT_LT(worst, 1e-5) << "|(Du(s) du, Dv(s) dv)| = 0.0625";
    EXPECT_LT(worstArea, 1e-6) << "area(P) = (2/16)^2";
    std::printf("NUMERICS case=derivative_step_ortho tolerance=1e-5 measured=%.3g\n", worst);
    std::printf("NUMERICS case=area_ortho tolerance=1e-6 measured=%.3g\n", worstArea);
}

// Perspective, fov 90 over 16 pixels: the footprint grows by 2/16 per unit of distance,
// so at the plane z = 5 straight ahead area(P) = (5 * 0.125)^2; the middle pixels'
// samples lie up to a pixel off the axis, which lengthens the distance and tilts the
// footprint: up to 5% more.
TEST(Derivatives, AreaGrowsWithDistanceInPerspective) {
    Rendered img = renderRib(shaderPath() +
                             "Format 16 16 1\nPixelSamples 1 1\nProjection \"perspective\" "
                             "\"fov\" 90\nWorldBegin\nTranslate 0 0 5\nSurface \"dstep\"\n"
                             "Patch \"bilinear\" \"P\" [-5 5 0  5 5 0  -5 -5 0  5 -5 0]\n"
                             "WorldEnd\n");
    const double expect = std::pow(5.0 * 0.125, 2);
    for (int y = 7; y <= 8; ++y)
        for (int x = 7; x <= 8; ++x) EXPECT_NEAR(img.at(x, y).b, 1.025 * expect, 0.025 * expect);
    // and twice as far, four times the area
    Rendered far = renderRib(shaderPath() +
                             "Format 16 16 1\nPixelSamples 1 1\nProjection \"perspective\" "
                             "\"fov\" 90\nWorldBegin\nTranslate 0 0 10\nSurface \"dstep\"\n"
                             "Patch \"bilinear\" \"P\" [-5 5 0  5 5 0  -5 -5 0  5 -5 0]\n"
                             "WorldEnd\n");
    EXPECT_NEAR(far.at(8, 8).b / img.at(8, 8).b, 4.0, 0.04);
}

// calculatenormal of an undisplaced P is N; Deriv(s*s, s) = 2 s on a cylinder, where s
// runs around and t along it (Deriv = Du(num)/Du(den) + Dv(num)/Dv(den), and t's
// direction does not change s). Forward differences: error about one footprint in s,
// which the cylinder's tilt toward its silhouette stretches (1.5x at the pixels kept).
TEST(Derivatives, CalculatenormalAndDerivOnACylinder) {
    Rendered img = renderRib(shaderPath() +
                             "Format 32 32 1\nPixelSamples 1 1\nProjection \"orthographic\"\n"
                             "ScreenWindow -1.2 1.2 -1.2 1.2\nWorldBegin\nTranslate 0 0 5\n"
                             "Rotate 90 1 0 0\nSurface \"dnormal\"\n"
                             "Cylinder 1 -1 1 360\nWorldEnd\n");
    int covered = 0;
    double worstN = 0, worstDeriv = 0;
    for (int y = 4; y < 28; ++y)
        for (int x = 6; x < 26; ++x) {  // away from the silhouette, where N turns fast
            const auto& p = img.at(x, y);
            if (p.a < 0.99f) continue;
            ++covered;
            worstN = std::fmax(worstN, std::fabs(p.r - 1.0));
            worstDeriv = std::fmax(worstDeriv, std::fabs(p.g));
        }
    EXPECT_GT(covered, 300);
    EXPECT_LT(worstN, 2.5e-3) << "calculatenormal(P) . N (forward difference: cos of half a step)";
    EXPECT_LT(worstDeriv, 0.03) << "Deriv(s*s, s) - 2s";
    std::printf("NUMERICS case=calculatenormal tolerance=2.5e-3 measured=%.3g\n", worstN);
    std::printf("NUMERICS case=deriv_forward_difference tolerance=0.03 measured=%.3g\n",
                worstDeriv);
}

// filterstep box-filters the step over s's footprint: the edge at s = 0.5 (x = 0) is
// anti-aliased (step() would give only 0 and 1), and each row still sums to the 32
// columns right of the edge.
TEST(Derivatives, FilterstepIsAntialiased) {
    Rendered img = orthoSquare(64, "Surface \"dfilter\"");
    int fractional = 0;
    double worstSum = 0;
    for (int y = 0; y < 64; ++y) {
        double sum = 0;
        for (int x = 0; x < 64; ++x) {
            double v = img.at(x, y).r;
            sum += v;
            if (v > 0.02 && v < 0.98) ++fractional;
            if (x < 30) {
                EXPECT_EQ(v, 0.0);
            }
            if (x > 33) {
                EXPECT_EQ(v, 1.0);
            }
        }
        worstSum = std::fmax(worstSum, std::fabs(sum - 32.0));
    }
    EXPECT_GT(fractional, 20) << "pixels on the edge take values between 0 and 1";
    EXPECT_LT(worstSum, 1.0);
}

// Displacement as bump: the height h = 0.1 sin(2 pi s) with s = (x + 1) / 2 tilts N by
// h'(x) = 0.1 pi cos(2 pi s), so a surface lit head-on shows 1 / sqrt(1 + h'^2) (matte,
// a distant light of intensity 1). Column means (the jitter of PixelSamples 1 averages
// out) against the closed form at the column's middle, moved half a footprint on (the
// forward difference; the triangles' frame is not along x, so where the slope is taken
// moves by up to another 0.3 footprint: 3e-3 in intensity); both the shader that sets N
// and the one that only moves P.
TEST(Derivatives, DisplacementBumpsTheNormal) {
    for (const char* shader : {"wave", "waveP"}) {
        Rendered img = orthoSquare(64, std::string("Surface \"matte\"\nDisplacement \"") +
                                           shader + "\"");
        double worst = 0, darkest = 1;
        for (int x = 2; x < 62; ++x) {
            double mean = img.mean(0, x, 0, x + 1, 64);
            double xc = -1.0 + (x + 0.5) / 32.0 + 0.5 / 32.0;
            double s = (xc + 1.0) / 2.0;
            double slope = 0.1 * kPi * std::cos(2 * kPi * s);
            worst = std::fmax(worst, std::fabs(mean - 1.0 / std::sqrt(1.0 + slope * slope)));
            darkest = std::fmin(darkest, mean);
        }
        EXPECT_LT(darkest, 0.96) << shader << ": the bumps show";
        EXPECT_LT(worst, 3e-3) << shader;
        std::printf("NUMERICS case=bump_%s tolerance=3e-3 measured=%.3g\n", shader, worst);
    }
}

// A displacement shader that cannot be found is reported and the surface renders flat.
TEST(Derivatives, MissingDisplacementIsLeftOut) {
    Rendered img = orthoSquare(16, "Surface \"matte\"\nDisplacement \"no_such_bump\"");
    EXPECT_NEAR(img.at(8, 8).r, 1.0, 1e-5);
}

