// furnace_test.cpp: case 6, white furnace: a closed box of polygons seen from inside,
// every wall emitting E and reflecting diffusely with albedo a (cosine-weighted trace()
// from RSL random()); the radiance is E (1 - a^(D+1)) / (1 - a) for D bounces, which is
// E / (1 - a) as D grows. Every path has the same value, so there is no Monte Carlo
// noise: any error is a leak through the box's seams, a lost bounce or rounding.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "numerics_util.h"

using namespace rd::numerics;

namespace {

const char* kFurnaceShader =
    "surface furnace(float albedo = 0.5, emission = 1;) {\n"
    "    normal Nf = faceforward(normalize(N), I);\n"
    "    vector A = abs(xcomp(Nf)) > 0.5 ? vector(0, 1, 0) : vector(1, 0, 0);\n"
    "    vector T = normalize(Nf ^ A);\n"
    "    vector B = Nf ^ T;\n"
    "    float u1 = random();\n"
    "    float u2 = random();\n"
    "    float r = sqrt(u1), phi = 6.28318531 * u2;\n"
    "    vector D = r * cos(phi) * T + r * sin(phi) * B + sqrt(max(0, 1 - u1)) * Nf;\n"
    "    Oi = 1;\n"
    "    Ci = emission + albedo * trace(P, D);\n"
    "}\n";

std::string shaderDir() {
    std::string dir = rd::test::scratchDir("raydrive_numerics_furnace");
    std::filesystem::create_directories(dir);
    std::ofstream(dir + "/furnace.sl") << kFurnaceShader;
    return dir;
}

// The cube [-1, 1]^3 as six polygons sharing their edges, the eye at its centre;
// `options` go before the camera (e.g. Russian roulette).
std::string furnace(double albedo, double emission, int depth, const std::string& options = "",
                    int res = 8, int spp = 1) {
    char buf[200];
    std::snprintf(buf, sizeof buf,
                  "Attribute \"trace\" \"int maxspeculardepth\" [%d]\n"
                  "Surface \"furnace\" \"albedo\" %.9g \"emission\" %.9g\n", depth, albedo,
                  emission);
    return "Option \"searchpath\" \"shader\" [\"" + shaderDir() + ":&\"]\n" + options +
           camera(res, 90, spp) +
           "WorldBegin\n" + buf +
           "Polygon \"P\" [-1 -1 1  1 -1 1  1 1 1  -1 1 1]\n"
           "Polygon \"P\" [-1 -1 -1  -1 1 -1  1 1 -1  1 -1 -1]\n"
           "Polygon \"P\" [1 -1 -1  1 1 -1  1 1 1  1 -1 1]\n"
           "Polygon \"P\" [-1 -1 -1  -1 -1 1  -1 1 1  -1 1 -1]\n"
           "Polygon \"P\" [-1 1 -1  -1 1 1  1 1 1  1 1 -1]\n"
           "Polygon \"P\" [-1 -1 -1  1 -1 -1  1 -1 1  -1 -1 1]\n"
           "WorldEnd\n";
}

}  // namespace

// Tolerance 1e-4 relative against the series to the depth the scene asks for (rounding
// of up to 65 additions, the 1e-6 weight cut); against the infinite series E / (1 - a)
// the truncation a^(D+1) adds to it, so that comparison is stated separately.
TEST(Numerics, WhiteFurnace) {
    const double e = 0.25;
    for (double a : {0.5, 0.9, 0.99}) {
        const int depth = a > 0.95 ? 1024 : 64;
        Diagnosed d = renderWithDiagnostics(furnace(a, e, depth));
        ASSERT_EQ(countOf(d.messages, "error"), 0) << d.messages;  // the shader compiled
        const double got = d.image.mean(0, 0, 0, d.image.width, d.image.height);
        double spread = 0;
        for (const rd::Rgba& p : d.image.pixels) spread = std::fmax(spread, std::fabs(p.r - got));
        const double series = e * (1.0 - std::pow(a, depth + 1)) / (1.0 - a);
        const double infinite = e / (1.0 - a);
        char name[80];
        std::snprintf(name, sizeof name, "furnace_a%g_depth%d_vs_series", a, depth);
        EXPECT_TRUE(report(name, 1e-4, std::fabs(got / series - 1.0) + spread / series))
            << "got " << got << " expected " << series << "\n" << d.messages;
        std::snprintf(name, sizeof name, "furnace_a%g_depth%d_vs_E/(1-a)", a, depth);
        const double tol = std::pow(a, depth + 1) + 1e-4;  // the truncation, stated
        EXPECT_TRUE(report(name, tol, std::fabs(got / infinite - 1.0)));
        EXPECT_EQ(d.image.stats.nonfiniteSamples, 0u);
    }
}

// Russian roulette keeps the furnace unbiased: with roulette from depth 2 and a depth
// limit deep enough that truncation is below 1e-40, the mean radiance is E / (1 - a)
// within its Monte Carlo error (every path is a random-length sum now); roulette ends
// paths, so far fewer rays are traced than without it.
TEST(Numerics, WhiteFurnaceWithRussianRouletteIsUnbiased) {
    const double e = 0.25, a = 0.9;
    Diagnosed d = renderWithDiagnostics(
        furnace(a, e, 1024, "Option \"trace\" \"int roulettedepth\" [2]\n", 16, 4));
    ASSERT_EQ(countOf(d.messages, "error"), 0) << d.messages;
    const auto& px = d.image.pixels;
    double sum = 0, sum2 = 0;
    for (const rd::Rgba& p : px) sum += p.r, sum2 += double(p.r) * p.r;
    const double n = double(px.size()), mean = sum / n;
    const double stderrOfMean = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
    const double expected = e / (1 - a);
    const double z = std::fabs(mean - expected) / stderrOfMean;
    std::printf("furnace with roulette: mean %.5f expected %.5f, standard error %.5f, z %.2f, "
                "roulette ended %llu rays\n", mean, expected, stderrOfMean, z,
                (unsigned long long)d.image.stats.rouletteEnded);
    EXPECT_TRUE(report("furnace_a0.9_roulette_z_score", 4.0, z));
    EXPECT_GT(d.image.stats.rouletteEnded, 0u);
    EXPECT_GT(stderrOfMean, 0.0);  // roulette makes paths random: there is noise now
    EXPECT_LT(stderrOfMean / expected, 0.05);
}
