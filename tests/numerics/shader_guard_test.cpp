// shader_guard_test.cpp: case 5, shaders that produce NaN, Inf, negative, huge (1e30) or
// denormal radiance, or such weights for traced rays, shadow rays and continuations:
// none of it reaches the film (which stays finite), and every fault is counted (--stats).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "numerics_util.h"

using namespace rd::numerics;

namespace {

// bad(a, b, where): the value a / b (computed on the device) as the emission (where 0),
// the weight of a trace() (1), the coefficient of a light (2), or the opacity (3).
const char* kBadShader =
    "surface bad(float a = 1, b = 1, where = 0;) {\n"
    "    color v = color(a / b);\n"
    "    normal Nf = faceforward(normalize(N), I);\n"
    "    Oi = 1;\n"
    "    if (where == 3) Oi = v;\n"
    "    Ci = (where == 0 ? v : color(0)) + (where == 1 ? v : color(0)) * trace(P, reflect(I, Nf))\n"
    "       + (where == 2 ? v : color(0)) * diffuse(Nf);\n"
    "}\n";

std::string shaderDir() {
    std::string dir = ::testing::TempDir() + "/raydrive_numerics_guard";
    std::filesystem::create_directories(dir);
    std::ofstream(dir + "/bad.sl") << kBadShader;
    return dir;
}

// The bad shader on the left half of a plane at z = 5, constant 0.5 grey on the right;
// behind the eye a small white constant square that trace() reaches, and a distant
// light at 60 degrees from the normal whose shadow rays pass beside that square.
std::string scene(double a, double b, int where) {
    char buf[200];
    std::snprintf(buf, sizeof buf, "Surface \"bad\" \"a\" %.9g \"b\" %.9g \"where\" %d\n", a,
                  b, where);
    return "Option \"searchpath\" \"shader\" [\"" + shaderDir() + ":&\"]\n" + camera(8, 40, 1) +
           "WorldBegin\nLightSource \"distantlight\" 1 \"from\" [0 0.8660254 -0.5] \"to\" [0 0 0]\n"
           "AttributeBegin\n" + buf +
           "Polygon \"P\" [-50 -50 5  0 -50 5  0 50 5  -50 50 5]\nAttributeEnd\n"
           "AttributeBegin\nSurface \"constant\"\nColor [0.5 0.5 0.5]\n"
           "Polygon \"P\" [0 -50 5  50 -50 5  50 50 5  0 50 5]\nAttributeEnd\n"
           "AttributeBegin\nSurface \"constant\"\n" + squareAtZ(-5.0, 5.0) +
           "AttributeEnd\nWorldEnd\n";
}

struct Fault {
    const char* name;
    double a, b;
    uint64_t rd::RenderStats::*counter;
};

}  // namespace

// Tolerance 0 (well, 1e-6): a dropped contribution is exactly zero; the left half is
// black with alpha 1 (alpha 0 where the opacity itself was bad), the right half 0.5.
TEST(Numerics, BadShaderResultsNeverReachTheFilm) {
    const Fault faults[] = {{"nan", 0, 0, &rd::RenderStats::shadeNonfinite},
                            {"inf", 1, 0, &rd::RenderStats::shadeNonfinite},
                            {"negative", -1, 1, &rd::RenderStats::shadeNegative},
                            {"huge", 1e30, 1, &rd::RenderStats::shadeHuge},
                            {"denormal", 1e-30, 1e10, &rd::RenderStats::shadeDenormal}};
    const char* whereName[] = {"emission", "trace_weight", "light_weight", "opacity"};
    for (const Fault& f : faults)
        for (int where = 0; where < 4; ++where) {
            Diagnosed d = renderWithDiagnostics(scene(f.a, f.b, where));
            const rd::test::Rendered& img = d.image;
            ASSERT_EQ(img.pixels.size(), 64u);
            const bool badAlpha = where == 3;  // (a denormal opacity is transparent too)
            double err = allFinite(img) ? 0.0 : INFINITY;
            for (int y = 0; y < 8; ++y)
                for (int x = 0; x < 8; ++x) {
                    const rd::Rgba& p = img.at(x, y);
                    const double c = x < 4 ? 0.0 : 0.5, alpha = x < 4 && badAlpha ? 0.0 : 1.0;
                    err = std::fmax(err, std::fmax(std::fabs(p.r - c), std::fabs(p.a - alpha)));
                }
            char name[64];
            std::snprintf(name, sizeof name, "bad_shader_%s_%s", f.name, whereName[where]);
            EXPECT_TRUE(report(name, 1e-6, err));
            EXPECT_GT(img.stats.*f.counter, 0u) << name << " must be counted";
            EXPECT_EQ(img.stats.nonfiniteSamples, 0u) << name;
            if (f.counter != &rd::RenderStats::shadeDenormal)
                EXPECT_EQ(countOf(d.messages, "left out of the image"), 1) << d.messages;
        }
}

// A well-behaved scene counts nothing and warns about nothing.
TEST(Numerics, GoodShadersCountNoFaults) {
    Diagnosed d = renderWithDiagnostics(scene(1, 2, 2));
    const auto& st = d.image.stats;
    EXPECT_EQ(st.shadeNonfinite + st.shadeNegative + st.shadeHuge + st.shadeDenormal, 0u);
    EXPECT_EQ(d.warnings, 0) << d.messages;
    EXPECT_NEAR(d.image.at(1, 4).r, 0.25, 1e-6);  // 0.5 * diffuse = 0.5 cos 60
}
