// curves_points_test.cpp: ribbons for Curves (width, orientation, counts) and discs for
// Points.
#include <cmath>

#include <gtest/gtest.h>

#include "host/scene/tessellate_curves_points.h"
#include "test_util.h"

using namespace rd;

TEST(Curves, LinearRibbonWidthAndCameraFacing) {
    CurvesInput in;
    in.nvertices = {3};
    in.P = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
    in.width = {0.2f, 0.4f, 0.6f};
    SurfaceMesh m;
    ASSERT_TRUE(tessellateCurves(in, glm::vec3(0, 0, 1), 2, m));
    test::expectWellFormed(m);
    EXPECT_EQ(m.mesh.p.size(), size_t(2 * (2 * 2 + 1)));
    EXPECT_EQ(m.mesh.tris.size() / 3, size_t(2 * 4));
    for (size_t j = 0; j < m.mesh.p.size() / 2; ++j) {
        glm::vec3 a = m.mesh.p[2 * j], b = m.mesh.p[2 * j + 1];
        float x = 0.5f * (a.x + b.x);
        EXPECT_NEAR(glm::length(b - a), 0.2f + 0.2f * x, 1e-5f);  // linear width
        EXPECT_NEAR(a.z, 0.0f, 1e-6f);                               // in the view plane
        EXPECT_NEAR(m.mesh.n[2 * j].z, -1.0f, 1e-5f);                 // faces the eye
    }
    EXPECT_NEAR(meshArea(m.mesh), 2.0 * 0.4, 1e-5);
}

TEST(Curves, NormalOrientedCubicBezier) {
    CurvesInput in;
    in.cubic = true;
    in.nvertices = {7};  // two bezier segments
    for (int i = 0; i < 7; ++i) in.P.emplace_back(float(i), 0.0f, 0.0f);
    in.N = {{0, 1, 0}, {0, 1, 0}, {0, 1, 0}};
    in.constantWidth = 0.5f;
    SurfaceMesh m;
    ASSERT_TRUE(tessellateCurves(in, glm::vec3(0, 0, 1), 4, m));
    test::expectWellFormed(m);
    EXPECT_EQ(m.mesh.p.size(), size_t(2 * (2 * 4 + 1)));
    for (size_t i = 0; i < m.mesh.p.size(); ++i) {
        EXPECT_NEAR(m.mesh.p[i].y, 0.0f, 1e-6f);           // ribbon perpendicular to N
        EXPECT_NEAR(std::fabs(m.mesh.p[i].z), 0.25f, 1e-6f);
        EXPECT_NEAR(m.mesh.n[i].y, 1.0f, 1e-5f);
    }
    EXPECT_NEAR(m.mesh.p.back().x, 6.0f, 1e-5f);
    EXPECT_NEAR(meshArea(m.mesh), 6.0 * 0.5, 1e-4);
}

TEST(Curves, PeriodicBSplineCountsAndBadInput) {
    CurvesInput in;
    in.cubic = true;
    in.periodic = true;
    in.vbasis = bSplineBasis();
    in.nvertices = {6, 4};
    for (int i = 0; i < 10; ++i) {
        float a = float(i) * 1.3f;
        in.P.emplace_back(std::cos(a), std::sin(a), float(i));
    }
    EXPECT_EQ(curveSegments(true, 6, true, 1), 6);
    EXPECT_EQ(curveVaryingCount(true, 6, true, 1), 6);
    EXPECT_EQ(curveVaryingCount(true, 7, false, 3), 3);
    EXPECT_EQ(curveVaryingCount(false, 5, false, 1), 5);
    EXPECT_EQ(curveSegments(false, 1, false, 1), -1);
    in.width.assign(10, 0.1f);
    SurfaceMesh m;
    ASSERT_TRUE(tessellateCurves(in, glm::vec3(0, 0, 1), 3, m));
    test::expectWellFormed(m);
    EXPECT_EQ(m.mesh.p.size(), size_t(2 * (6 * 3 + 1) + 2 * (4 * 3 + 1)));
    EXPECT_EQ(m.faceIndex.back(), 1);
    // closed: the end of each curve meets its start
    EXPECT_NEAR(glm::length(m.mesh.p[0] - m.mesh.p[2 * 18]), 0.0f, 1e-5f);
    std::string err;
    in.width.assign(9, 0.1f);
    EXPECT_FALSE(tessellateCurves(in, glm::vec3(0, 0, 1), 3, m, &err));
    EXPECT_FALSE(err.empty());
    in.width.clear();
    in.P.pop_back();
    EXPECT_FALSE(tessellateCurves(in, glm::vec3(0, 0, 1), 3, m, &err));
    CurvesInput bad;
    bad.cubic = true;
    bad.nvertices = {5};  // (5-4) % 3 != 0 for bezier
    bad.P.assign(5, glm::vec3(0.0f));
    EXPECT_FALSE(tessellateCurves(bad, glm::vec3(0, 0, 1), 3, m, &err));
}

TEST(Points, CameraFacingDiscs) {
    std::vector<glm::vec3> P = {{0, 0, 0}, {3, 1, 2}};
    SurfaceMesh m;
    ASSERT_TRUE(tessellatePoints(P, {1.0f, 2.0f}, 1.0f, glm::vec3(1, 1, 0), 16, m));
    test::expectWellFormed(m);
    EXPECT_EQ(m.mesh.p.size(), size_t(2 * 17));
    EXPECT_EQ(m.mesh.tris.size() / 3, size_t(2 * 16));
    glm::vec3 view = glm::normalize(glm::vec3(1, 1, 0));
    for (int i = 1; i <= 16; ++i) {
        EXPECT_NEAR(glm::length(m.mesh.p[i] - P[0]), 0.5f, 1e-5f);
        EXPECT_NEAR(glm::length(m.mesh.p[17 + i] - P[1]), 1.0f, 1e-5f);
        EXPECT_NEAR(glm::dot(m.mesh.p[i] - P[0], view), 0.0f, 1e-5f);
    }
    EXPECT_NEAR(glm::dot(m.mesh.n[0], view), -1.0f, 1e-5f);
    EXPECT_EQ(m.faceIndex.back(), 1);
    std::string err;
    EXPECT_FALSE(tessellatePoints(P, {1.0f}, 1.0f, glm::vec3(0, 0, 1), 8, m, &err));
    EXPECT_FALSE(tessellatePoints(P, {}, 1.0f, glm::vec3(0, 0, 0), 8, m, &err));
}
