// volume_shadows_test.cpp: shadow rays from inside volumes (RT_VOLUME_SHADOWS,
// cl/lib/volume.clh). A volume shader that marches its segment and adds the lights it
// sees at each step gets each light's shadow ray from one of its steps, picked at
// random and weighted by the number of steps that see the light: a light shaft. Before
// session 42 a volume's illuminance loops saw every light unshadowed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "render_harness.h"

using rd::test::Rendered;
using rd::test::renderRib;

namespace {

const char* const kShaders[][2] = {
    // single scattering by a march of `steps` midpoints from the eye to P
    {"scatter",
     "volume scatter(float sigma = 0.1; float steps = 40) {\n"
     "  point P0 = P - I;\n  float len = length(I);\n  color sum = 0;\n  float k;\n"
     "  for (k = 0; k < steps; k += 1) {\n"
     "    point Pk = P0 + I * ((k + 0.5) / steps);\n"
     "    illuminance(Pk) { sum += Cl; }\n  }\n"
     "  Ci = Ci + sigma * len / steps * sum;\n}\n"},
    // the lights seen at P alone: one evaluation a light
    {"atp", "volume atp() {\n  illuminance(P) { Ci += 0.5 * Cl; }\n}\n"},
    // a shader's NaN points: where the lights are seen, and where a ray is traced from
    {"nanv",
     "volume nanv(float big = 1e30) {\n  point Pk = P * (big * big - big * big);\n"
     "  illuminance(Pk) { Ci += 0.5 * Cl; }\n}\n"},
    {"nantrace",
     "surface nantrace(float big = 1e30) {\n"
     "  Ci = 0.5 * trace(P * (big * big - big * big), vector(0, 0, -1));\n}\n"},
};

// Orthographic eye rays along +z from z = 0 over [-1, 1]^2 to a wall at z = 10 (its
// surface call `wall`), through the atmosphere "scatter"; `above`: lights and occluders.
std::string shaftScene(const std::string& dir, const std::string& above,
                       const std::string& wall = "Surface \"constant\"\nColor [0 0 0]\n",
                       const std::string& options = "",
                       const std::string& volume = "scatter") {
    return "Option \"searchpath\" \"shader\" [\"" + dir + ":&\"]\n" + options +
           "Format 16 16 1\nPixelSamples 4 4\nOption \"render\" \"float pixelerror\" "
           "[1e-9]\n"
           "Projection \"orthographic\"\nScreenWindow -1 1 -1 1\nWorldBegin\n" +
           above + "Atmosphere \"" + volume + "\"\nAttributeBegin\n" + wall +
           "Polygon \"P\" [-100 -100 10  100 -100 10  100 100 10  -100 100 10]\n"
           "AttributeEnd\nWorldEnd\n";
}

// A square at y = 2, above every eye ray, over x in [-100, 100] and z from -100 to zEnd.
std::string roofTo(double zEnd) {
    const std::string z = std::to_string(zEnd);
    return "AttributeBegin\nSurface \"constant\"\nPolygon \"P\" [-100 2 -100  100 2 -100 "
           " "
           "100 2 " +
           z + "  -100 2 " + z + "]\nAttributeEnd\n";
}

const char* const kSun =
    "LightSource \"distantlight\" 1 \"from\" [0 1 0] \"to\" [0 0 0]\n";

double worstAgainst(const Rendered& r, double expect) {
    double worst = 0;
    for (int y = 0; y < r.height; ++y)
        for (int x = 0; x < r.width; ++x)
            worst = std::max(worst, std::fabs(double(r.at(x, y).r) - expect));
    return worst;
}

bool hasFeature(const Rendered& r, const char* name) {
    const auto names = r.stats.features.names();
    return std::find(names.begin(), names.end(), name) != names.end();
}

}  // namespace

// Light from straight above; a roof over z < 5 shades the first half of every eye ray's
// 10 units: of the march's 40 steps (each adding 0.1 x 10 / 40 of the light's Cl of 1)
// the 20 past z = 5 see the light, 0.5 (all: 1). Each sample traces one shadow ray from
// a step picked uniformly, worth 40 steps: under the Sobol sampler a pixel's 16 picks are
// stratified, 8 on each side, so every pixel is 0.5; with independent samples the image's
// mean is (4096 samples of 0 or 1). A roof over everything: 0; none: 1. A treelet budget
// of 512 bytes traces the shadow rays through treelets: the same image.
TEST(VolumeShadows, RoofCastsAShaftThroughTheMarch) {
    const std::string dir = rd::test::shaderFolder("raydrive_volume_shadows", kShaders);
    const std::string sun = kSun;
    const Rendered half = renderRib(shaftScene(dir, sun + roofTo(5)));
    EXPECT_LT(worstAgainst(half, 0.5), 1e-5) << "half the march in the roof's shadow";
    EXPECT_NEAR(half.mean(3, 0, 0, 16, 16), 1.0, 1e-6);
    EXPECT_TRUE(hasFeature(half, "volume_shadows"));
    EXPECT_LT(worstAgainst(renderRib(shaftScene(dir, sun + roofTo(-50))), 1.0), 1e-5)
        << "no roof over the march";
    EXPECT_LT(worstAgainst(renderRib(shaftScene(dir, sun + roofTo(50))), 0.0), 1e-6)
        << "the whole march under the roof";
    const Rendered independent = renderRib(
        shaftScene(dir, sun + roofTo(5), "Surface \"constant\"\nColor [0 0 0]\n",
                   "Option \"render\" \"string sampler\" [\"independent\"]\n"));
    EXPECT_NEAR(independent.mean(0, 0, 0, 16, 16), 0.5, 0.04)
        << "4096 samples of 0 or 1: 0.008 standard error";
    rd::RenderSettings treelets;
    treelets.treeletBytes = 512;
    const Rendered streamed = renderRib(shaftScene(dir, sun + roofTo(5)), treelets);
    EXPECT_TRUE(hasFeature(streamed, "treelets"));
    EXPECT_LT(worstAgainst(streamed, 0.5), 1e-5);
}

// A point light of intensity 100 at (0, 10, 5): each step sees Cl = 100 / d^2, from 0.8
// to 1, so the picked step's weight (40 times its own part) differs from step to step.
// Each pixel against the march's sum at its centre: open, and under the roof over z < 5
// (a shadow ray from a step before z = 5 crosses y = 2 before z = 5, one after it after).
TEST(VolumeShadows, PointLightStepsWeighByTheirOwnLight) {
    const std::string dir = rd::test::shaderFolder("raydrive_volume_shadows", kShaders);
    const std::string lamp =
        "LightSource \"pointlight\" 1 \"from\" [0 10 5] \"intensity\" 100\n";
    // the march's sum at (x, y), averaged over the pixel (8 x 8 points: its box filter)
    auto expect = [](int px, int py, bool roof) {
        double mean = 0;
        for (int j = 0; j < 8; ++j)
            for (int i = 0; i < 8; ++i) {
                const double x = (px + (i + 0.5) / 8) / 8 - 1,
                             y = 1 - (py + (j + 0.5) / 8) / 8;
                double sum = 0;
                for (int k = 0; k < 40; ++k) {
                    const double z = 10 * (k + 0.5) / 40;
                    if (roof && z < 5) continue;
                    sum += 100 / (x * x + (10 - y) * (10 - y) + (5 - z) * (5 - z));
                }
                mean += 0.1 * 10 / 40 * sum / 64;
            }
        return mean;
    };
    for (bool roof : {false, true}) {
        const Rendered r =
            renderRib(shaftScene(dir, lamp + (roof ? roofTo(5) : roofTo(-50))));
        double worst = 0;
        for (int py = 0; py < 16; ++py)
            for (int px = 0; px < 16; ++px)
                worst = std::max(worst, std::fabs(r.at(px, py).r - expect(px, py, roof)));
        // (a pixel's 16 picks stratified over steps whose light differs by up to 20%)
        EXPECT_LT(worst, 0.02) << (roof ? "under the roof" : "open");
        std::printf(
            "NUMERICS case=volume_shadow_point_light_%s tolerance=0.02 measured=%.3g\n",
            roof ? "roof" : "open", worst);
    }
}

// The surface's shadow rays and the volume's share the pool (a light's two slots): the
// wall is matte (Cs 0.2) under a second distant light from the camera's side, which the
// volume sees at every step too (1.0), beside the sun's shaft (0.5): 0.2 + 1 + 0.5. The
// standard fog atmosphere, which loops over no light, leaves the program without volume
// shadows.
TEST(VolumeShadows, SurfaceAndVolumeShadowRaysTogether) {
    const std::string dir = rd::test::shaderFolder("raydrive_volume_shadows", kShaders);
    const std::string lights =
        std::string(kSun) +
        "LightSource \"distantlight\" 2 \"from\" [0 0 0] \"to\" [0 0 1]\n";
    const Rendered r = renderRib(
        shaftScene(dir, lights + roofTo(5), "Surface \"matte\"\nColor [0.2 0.2 0.2]\n"));
    EXPECT_LT(worstAgainst(r, 1.7), 1e-4);
    const Rendered fog = renderRib(
        "Format 8 8 1\nPixelSamples 2 2\nProjection \"orthographic\"\nWorldBegin\n" +
        std::string(kSun) +
        "Atmosphere \"fog\"\nSurface \"matte\"\nPolygon \"P\" [-9 -9 5  9 -9 5  9 9 5  "
        "-9 9 5]\n"
        "WorldEnd\n");
    EXPECT_TRUE(hasFeature(fog, "atmosphere"));
    EXPECT_FALSE(hasFeature(fog, "volume_shadows"));
}

// A volume that sees the lights at P alone (one evaluation a light: no pick) traces its
// shadow ray from P: the wall at z = 10 under a roof reaching z = 50 is in its shadow
// (0), under one reaching z = 5 it is lit (0.5).
TEST(VolumeShadows, OneEvaluationTracesFromWhereItWasMade) {
    const std::string dir = rd::test::shaderFolder("raydrive_volume_shadows", kShaders);
    const std::string wall = "Surface \"constant\"\nColor [0 0 0]\n";
    const std::string sun = kSun;
    EXPECT_LT(
        worstAgainst(renderRib(shaftScene(dir, sun + roofTo(50), wall, "", "atp")), 0.0),
        1e-6);
    EXPECT_LT(
        worstAgainst(renderRib(shaftScene(dir, sun + roofTo(5), wall, "", "atp")), 0.5),
        1e-6);
}

// A shader's NaN point is a fault of its own, not a hang: a volume seeing the lights
// there sends no shadow ray (counted among the shaders' NaN/Inf), and a ray traced from
// there meets nothing. Before, the eight-ray packet walk (shadow and closest-hit packets)
// never ended on a lane whose origin was NaN: the render hung.
TEST(VolumeShadows, NanPointsSendNoRay) {
    const std::string dir = rd::test::shaderFolder("raydrive_volume_shadows", kShaders);
    const Rendered v = renderRib(
        shaftScene(dir, kSun, "Surface \"constant\"\nColor [0 0 0]\n", "", "nanv"));
    EXPECT_TRUE(hasFeature(v, "shadow_packets"));
    EXPECT_LT(worstAgainst(v, 0.0), 1e-6);
    EXPECT_GT(v.stats.shadeNonfinite, 0u);
    const Rendered t = renderRib(shaftScene(dir, kSun, "Surface \"nantrace\"\n"));
    EXPECT_TRUE(hasFeature(t, "closest_packets"));
    EXPECT_NEAR(t.mean(3, 0, 0, 16, 16), 1.0, 1e-6);
}
