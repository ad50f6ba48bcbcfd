// specular_test.cpp: case 2, deep specular paths: two parallel mirrors facing each other
// with the camera between them; each bounce adds the ambient term, so a pixel is the
// geometric series sum_{k=0..D} Kr^k for Attribute "trace" "maxspeculardepth" D.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

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
        for (int depth : {1, 2, 8, 64}) {
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

// A depth beyond 64 is held at 64: the work stays bounded whatever the RIB asks.
TEST(Numerics, SpecularDepthIsBounded) {
    Diagnosed d = renderWithDiagnostics(mirrors(0.9, 100000));
    const auto& st = d.image.stats;
    EXPECT_EQ(st.features.maxSpecularDepth, 64);
    EXPECT_EQ(st.continuationRays, 64u * st.eyeRays);
    const double expected = (1.0 - std::pow(0.9, 65)) / 0.1;
    double err = std::fabs(d.image.mean(0, 0, 0, 8, 8) / expected - 1.0);
    EXPECT_TRUE(report("mirrors_depth_clamped_to_64", 2e-5, err));
}
