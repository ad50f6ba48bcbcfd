// quadric_bounds_test.cpp: the world boxes of placed quadrics (quadricWorldBounds): every
// kind, rotated, scaled and moved at random, contains its whole surface (points on a
// (u, v) grid), and a rotated shape's box is its end circles' (a sphere's its
// ellipsoid's), not the rotated corners of its object box; an instance keeps its corners.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "render_harness.h"
#include "scene/quadric_shapes.h"

using namespace rd;

namespace {

bool inside(const Aabb& b, glm::vec3 p) {
    for (int a = 0; a < 3; ++a)
        if (!(p[a] >= b.lo[a] && p[a] <= b.hi[a])) return false;
    return true;
}

}  // namespace

TEST(QuadricBounds, EveryKindLiesInItsBox) {
    const char* shapes[] = {"Sphere 1 -1 1 360",        "Sphere 0.8 -0.2 0.5 250",
                            "Cylinder 0.5 -1 2 360",    "Cone 1.5 0.7 -300",
                            "Disk 0.3 1.2 360",         "Paraboloid 0.9 0.2 1.4 360",
                            "Hyperboloid 0.3 -0.4 -0.6 0.9 0.2 0.7 360",
                            "Hyperboloid 1 0 0.5 0.2 1 0.5 180", "Torus 1 0.3 0 360 270"};
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> U(-1, 1);
    int points = 0;
    for (const char* shape : shapes) {
        for (int k = 0; k < 20; ++k) {
            char placement[256];
            std::snprintf(placement, sizeof placement,
                          "Translate %g %g %g Rotate %g %g %g %g Scale %g %g %g ", 50 * U(rng),
                          50 * U(rng), 50 * U(rng), 180 * U(rng), U(rng), U(rng), U(rng) + 1.5f,
                          1.5f + U(rng), 1.5f + U(rng), 1.5f + U(rng));
            const Scene s = test::sceneOfWorld(std::string(placement) + shape);
            ASSERT_EQ(s.quadrics.size(), 1u) << shape;
            const Quadric& q = s.quadrics[0];
            const Aabb& box = s.quadricBounds[0];
            for (int i = 0; i <= 24; ++i)
                for (int j = 0; j <= 24; ++j, ++points) {
                    const glm::vec3 p = quadricToWorld(q, quadricObjectPoint(q, i / 24.0f, j / 24.0f));
                    ASSERT_TRUE(inside(box, p)) << shape << " " << placement << " at (" << i
                                                << ", " << j << ")";
                }
        }
    }
    EXPECT_EQ(points, 9 * 20 * 625);
}

// A sphere turned 45 degrees about two axes: its box is 2 r wide on every axis (its
// object box's corners gave up to 2 sqrt(3) r); a turned cylinder's is its end circles'.
TEST(QuadricBounds, RotatedShapesGetTightBoxes) {
    const Scene sphere = test::sceneOfWorld("Rotate 45 1 0 0 Rotate 45 0 1 0 Sphere 2 -2 2 360");
    for (int a = 0; a < 3; ++a) {
        const float w = sphere.quadricBounds[0].hi[a] - sphere.quadricBounds[0].lo[a];
        EXPECT_NEAR(w, 4.0f, 4e-4f) << "axis " << a;
    }
    // a cylinder of radius 1 from z = 0 to 3, its axis turned to (0, sin 30, cos 30):
    // along y its end circles span 3 sin 30 + 2 cos 30, along z 3 cos 30 + 2 sin 30
    const Scene cyl = test::sceneOfWorld("Rotate -30 1 0 0 Cylinder 1 0 3 360");
    const Aabb& b = cyl.quadricBounds[0];
    const float s30 = 0.5f, c30 = std::sqrt(3.0f) / 2;
    EXPECT_NEAR(b.hi[0] - b.lo[0], 2.0f, 4e-4f);
    EXPECT_NEAR(b.hi[1] - b.lo[1], 3 * s30 + 2 * c30, 4e-4f);
    EXPECT_NEAR(b.hi[2] - b.lo[2], 3 * c30 + 2 * s30, 4e-4f);
}

// An instance of a square centred on its axis (a box that looks like a quadric's) keeps the
// corners of its prototype's box: turned 45 degrees it spans sqrt(2) on x and y.
TEST(QuadricBounds, InstancesKeepTheirPrototypesCorners) {
    const Scene s = test::sceneOfWorld(
        "ObjectBegin \"sq\" Polygon \"P\" [-0.5 -0.5 0  0.5 -0.5 0  0.5 0.5 0  -0.5 0.5 0] "
        "ObjectEnd Rotate 45 0 0 1 ObjectInstance \"sq\"");
    ASSERT_EQ(s.quadrics.size(), 1u);
    ASSERT_EQ(s.quadrics[0].kind, RT_Q_INSTANCE);
    for (int a = 0; a < 2; ++a)
        EXPECT_NEAR(s.quadricBounds[0].hi[a] - s.quadricBounds[0].lo[a], std::sqrt(2.0f), 1e-4f);
}
