// specular_test.cpp: case 2, deep specular paths: two parallel mirrors facing each other
// with the camera between them; each bounce adds the ambient term, so a pixel is the
// geometric series sum_{k=0..D} Kr^k for Attribute "trace" "maxspeculardepth" D.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "numerics_util.h"

using namespace rd::numerics;

namespace {

// Mirrors (standard "mirror", Ka 1 under an ambient light of 1: emission 1 per bounce)
// at z = 5 and z = -5; the eye at the origin looks at the first through a 4 degree fov,
// so 64 bounces drift 22 units sideways on mirrors 100 units across.
std::string mirrors(double kr, int depth) {
    char buf[160];
    std::snprintf(buf, sizeof buf,
                  "Attribute \"trace\" \"int maxspeculardepth\" [%d]\n"
                  "Surface \"mirror\" \"Ka\" 1 \"Kr\" %.9g\n", depth, kr);
    return camera(8, 4, 1) + "WorldBegin\nLightSource \"ambientlight\" 1 \"intensity\" 1\n" +
           buf + squareAtZ(5.0) + squareAtZ(-5.0) + "WorldEnd\n";
}

}  // namespace

// Tolerance 2e-5 relative: up to 65 float additions into the sample, and the 1e-6 weight
// below which a traced ray is not spawned (Kr = 0.5 stops after 20 bounces: 2e-6).
TEST(Numerics, MirrorsGiveTheGeometricSeries) {
    for (double kr : {0.5, 0.9}) {
        for (int depth : {1, 8, 64}) {
            Diagnosed d = renderWithDiagnostics(mirrors(kr, depth));
            const double expected = (1.0 - std::pow(kr, depth + 1)) / (1.0 - kr);
            double err = 0;
            for (const rd::Rgba& p : d.image.pixels)
                for (float c : {p.r, p.g, p.b})
                    err = std::fmax(err, std::fabs(c / expected - 1.0));
            char name[64];
            std::snprintf(name, sizeof name, "mirrors_Kr%g_depth%d", kr, depth);
            EXPECT_TRUE(report(name, 2e-5, err)) << "expected " << expected;
            const auto& st = d.image.stats;
            EXPECT_EQ(st.features.maxSpecularDepth, depth);
            // Bounded work: exactly one traced ray per bounce while the weight is above
            // 1e-6 (0.9^64 is), none past the depth, where the cut is counted.
            if (kr == 0.9) {
                EXPECT_EQ(st.continuationRays, uint64_t(depth) * st.eyeRays) << name;
                EXPECT_EQ(st.specularDepthCut, st.eyeRays) << name;
            } else {
                EXPECT_LE(st.continuationRays, uint64_t(std::min(depth, 20)) * st.eyeRays);
            }
        }
    }
}

// A depth beyond 4096 is held at 4096: the work stays bounded whatever the RIB asks (and
// here the 1e-6 weight cut ends the paths after 131 bounces).
TEST(Numerics, SpecularDepthIsBounded) {
    Diagnosed d = renderWithDiagnostics(mirrors(0.9, 100000));
    const auto& st = d.image.stats;
    EXPECT_EQ(st.features.maxSpecularDepth, 4096);
    EXPECT_LE(st.continuationRays, 131u * st.eyeRays);
    double err = std::fabs(d.image.mean(0, 0, 0, 8, 8) / 10.0 - 1.0);
    EXPECT_TRUE(report("mirrors_Kr0.9_depth_4096", 2e-5, err));
}

namespace {
// Two trace() calls per hit, each of weight 0.5, emission 1: D bounces give D + 1, with
// 2^D rays per eye ray at depth D.
std::string twins(int depth) {
    std::string dir = rd::test::scratchDir("raydrive_numerics_twin");
    std::filesystem::create_directories(dir);
    std::ofstream(dir + "/twin.sl")
        << "surface twin() {\n    normal Nf = faceforward(normalize(N), I);\n"
           "    vector R = reflect(I, Nf);\n    Oi = 1;\n"
           "    Ci = 1 + 0.5 * trace(P, R) + 0.5 * trace(P, R);\n}\n";
    char buf[96];
    std::snprintf(buf, sizeof buf, "Attribute \"trace\" \"int maxspeculardepth\" [%d]\n", depth);
    return "Option \"searchpath\" \"shader\" [\"" + dir + ":&\"]\n" + camera(8, 4, 1) +
           "WorldBegin\n" + buf + "Surface \"twin\"\n" + squareAtZ(5.0) + squareAtZ(-5.0) +
           "WorldEnd\n";
}
}  // namespace

// A ray tree that outgrows the ray pool (2^12 rays per eye ray, a pool of 64) loses the
// rays past the pool, counted and reported once, never written out of bounds; one that
// fits is exact.
TEST(Numerics, RayTreeLargerThanThePoolIsBounded) {
    Diagnosed fits = renderWithDiagnostics(twins(5));
    double err = std::fabs(fits.image.mean(0, 0, 0, 8, 8) / 6.0 - 1.0);
    EXPECT_TRUE(report("ray_tree_depth5_fits_pool", 2e-5, err));
    EXPECT_EQ(fits.image.stats.overflowRays, 0u);
    rd::RenderSettings small;
    small.poolCapacity = 64;
    Diagnosed over = renderWithDiagnostics(twins(12), small);
    EXPECT_TRUE(allFinite(over.image));
    EXPECT_GT(over.image.stats.overflowRays, 0u);
    EXPECT_LE(maxAbs(over.image), 13.0 + 1e-3);
    EXPECT_EQ(countOf(over.messages, "ray pool"), 1) << over.messages;
    // the first time a sample's tree overflowed it was aborted and issued again
    EXPECT_GT(over.image.stats.reissuedSamples, 0u);
}

// Ray trees that outgrow the pool wait on the spill stack instead of being lost: with a
// pool of 64 rays, 127-ray trees (depth 6) give exactly the series D + 1 = 7, the same
// image as a pool that holds them all, and the pool stays full while eye rays refill it
// beside the trees' rays (pool fill above 0.7, the goal).
TEST(Numerics, RayTreesSpillAndTheImageDoesNotDependOnThePool) {
    Diagnosed big = renderWithDiagnostics(twins(6));
    rd::RenderSettings small;
    small.poolCapacity = 64;
    Diagnosed tiny = renderWithDiagnostics(twins(6), small);
    const auto& st = tiny.image.stats;
    EXPECT_GT(st.spilledRays, 0u);
    EXPECT_EQ(st.overflowRays, 0u);
    EXPECT_EQ(st.reissuedSamples, 0u);
    EXPECT_EQ(countOf(tiny.messages, "ray pool"), 0) << tiny.messages;
    ASSERT_EQ(big.image.pixels.size(), tiny.image.pixels.size());
    double err = 0;
    for (size_t i = 0; i < big.image.pixels.size(); ++i) {
        err = std::fmax(err, std::fabs(tiny.image.pixels[i].r / 7.0 - 1.0));
        // the same sums in another order of rounds: within float rounding of 7
        EXPECT_NEAR(tiny.image.pixels[i].r, big.image.pixels[i].r, 2e-6) << i;
    }
    EXPECT_TRUE(report("twins_depth6_pool64", 1e-6, err));
    EXPECT_GT(st.poolFill, 0.7) << "rounds " << st.iterations;
    EXPECT_EQ(st.retiredSamples, st.eyeRays);
}

// Attribute "trace" "maxspeculardepth" is each object's own (session 35; before, the
// deepest any object asked for held for all): the front mirror (the eye's first hit, at
// even depths) and the back one (odd depths) send a reflection only while the ray that
// hit them is shallower than their own limit. Front 4, back 1: 1 + Kr; front 2, back 8:
// 1 + Kr + Kr^2; front 3, back 3: as one limit of 3.
TEST(Numerics, SpecularDepthIsEachObjectsOwn) {
    const double kr = 0.5;
    struct Case {
        int front, back, bounces;
    };
    for (const Case c : {Case{4, 1, 1}, Case{2, 8, 2}, Case{3, 3, 3}}) {
        char front[200], back[200];
        std::snprintf(
            front, sizeof front,
            "AttributeBegin\nAttribute \"trace\" \"int maxspeculardepth\" [%d]\n",
            c.front);
        std::snprintf(back, sizeof back,
                      "AttributeEnd\nAttributeBegin\n"
                      "Attribute \"trace\" \"int maxspeculardepth\" [%d]\n",
                      c.back);
        Diagnosed d = renderWithDiagnostics(
            camera(8, 4, 1) +
            "WorldBegin\nLightSource \"ambientlight\" 1 \"intensity\" 1\n" +
            "Surface \"mirror\" \"Ka\" 1 \"Kr\" 0.5\n" + front + squareAtZ(5.0) + back +
            squareAtZ(-5.0) + "AttributeEnd\nWorldEnd\n");
        const double expected = (1.0 - std::pow(kr, c.bounces + 1)) / (1.0 - kr);
        double err = 0;
        for (const rd::Rgba& p : d.image.pixels)
            err = std::fmax(err, std::fabs(p.r / expected - 1.0));
        EXPECT_LT(err, 2e-5) << c.front << " " << c.back << ": expected " << expected;
        EXPECT_EQ(d.image.stats.features.maxSpecularDepth, std::max(c.front, c.back));
        EXPECT_EQ(d.image.stats.features.materialDepths, c.front != c.back);
    }
}

// Attribute "trace" "maxdiffusedepth" (session 35; ignored before): two facing planes
// 2e4 across, each 1 + 0.5 indirectdiffuse() (four rays a hit, all meeting the other
// plane but one in 10^6). A path ends its diffuse bounces at the limit: 0 gives 1, 1
// gives 1 + 0.5; none given, the default maxspeculardepth 2 bounds them (1 + 0.5 +
// 0.25), and a maxspeculardepth of 8 with maxdiffusedepth 1 still 1.5.
TEST(Numerics, DiffuseDepthBoundsIndirectDiffuse) {
    const std::string dir = rd::test::scratchDir("raydrive_numerics_bounce");
    std::filesystem::create_directories(dir);
    std::ofstream(dir + "/bounce.sl")
        << "surface bounce() {\n    normal Nf = faceforward(normalize(N), I);\n"
           "    Oi = 1;\n    Ci = 1 + 0.5 * indirectdiffuse(P, Nf, 4);\n}\n";
    struct Case {
        const char* attributes;
        double expected;
    };
    for (const Case c :
         {Case{"", 1.75}, Case{"\"int maxdiffusedepth\" [0]", 1.0},
          Case{"\"int maxdiffusedepth\" [1]", 1.5},
          Case{"\"int maxdiffusedepth\" [1] \"int maxspeculardepth\" [8]", 1.5}}) {
        const std::string trace =
            *c.attributes ? "Attribute \"trace\" " + std::string(c.attributes) + "\n"
                          : "";
        Diagnosed d = renderWithDiagnostics(
            "Option \"searchpath\" \"shader\" [\"" + dir + ":&\"]\n" + camera(8, 4, 1) +
            "WorldBegin\n" + trace + "Surface \"bounce\"\n" + squareAtZ(5.0, 1e4) +
            squareAtZ(-5.0, 1e4) + "WorldEnd\n");
        EXPECT_NEAR(d.image.mean(0, 0, 0, 8, 8), c.expected, 1e-4) << c.attributes;
    }
}
