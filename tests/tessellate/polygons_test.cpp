// polygons_test.cpp: GeneralPolygon / PointsGeneralPolygons triangulation: concave
// outlines, holes, planes in 3D, duplicates, collinear and degenerate input.
#include <cmath>

#include <gtest/gtest.h>

#include "host/scene/tessellate_polygons.h"
#include "test_util.h"

using namespace rd;

namespace {
double shoelace(const std::vector<glm::vec3>& p) {
    double a = 0;
    for (size_t i = 0, j = p.size() - 1; i < p.size(); j = i++)
        a += double(p[j].x) * p[i].y - double(p[i].x) * p[j].y;
    return 0.5 * a;
}
// Every triangle wound counter-clockwise about n.
void expectWinding(const SurfaceMesh& m, glm::vec3 n) {
    for (size_t k = 0; k < m.mesh.tris.size(); k += 3) {
        const auto& P = m.mesh.p;
        glm::vec3 g = glm::cross(P[m.mesh.tris[k + 1]] - P[m.mesh.tris[k]],
                                 P[m.mesh.tris[k + 2]] - P[m.mesh.tris[k]]);
        EXPECT_GT(glm::dot(g, n), 0.0f);
    }
}
}  // namespace

TEST(Polygons, ConcaveLShapeAndStar) {
    std::vector<glm::vec3> L = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}};
    SurfaceMesh m;
    ASSERT_TRUE(tessellateGeneralPolygon({6}, L, m));
    test::expectWellFormed(m);
    EXPECT_EQ(m.mesh.tris.size(), 12u);
    EXPECT_NEAR(meshArea(m.mesh), 3.0, 1e-6);
    expectWinding(m, {0, 0, 1});
    // 7-point star, clockwise: winding follows the given order (normal -z).
    std::vector<glm::vec3> star;
    for (int i = 0; i < 14; ++i) {
        float a = -float(i) * float(M_PI) / 7.0f, r = i % 2 ? 0.4f : 1.0f;
        star.emplace_back(r * std::cos(a), r * std::sin(a), 0.0f);
    }
    SurfaceMesh s;
    ASSERT_TRUE(tessellateGeneralPolygon({14}, star, s));
    EXPECT_EQ(s.mesh.tris.size(), 12u * 3u);
    EXPECT_NEAR(meshArea(s.mesh), std::fabs(shoelace(star)), 1e-5);
    expectWinding(s, {0, 0, -1});
}

TEST(Polygons, SquareWithHolesIn3D) {
    // 4x4 square with a 2x2 and a 0.5x0.5 hole, in a tilted plane.
    std::vector<glm::vec3> p = {{0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0},          // outer CCW
                                {1, 1, 0}, {3, 1, 0}, {3, 3, 0}, {1, 3, 0},          // hole CCW too
                                {3.2f, 3.2f, 0}, {3.2f, 3.7f, 0}, {3.7f, 3.7f, 0}, {3.7f, 3.2f, 0}};
    glm::mat3 rot = glm::mat3(glm::vec3(0.6f, 0.0f, 0.8f), glm::vec3(0.0f, 1.0f, 0.0f),
                              glm::vec3(-0.8f, 0.0f, 0.6f));
    for (auto& q : p) q = rot * q + glm::vec3(5, -2, 1);
    SurfaceMesh m;
    ASSERT_TRUE(tessellateGeneralPolygon({4, 4, 4}, p, m));
    test::expectWellFormed(m);
    EXPECT_NEAR(meshArea(m.mesh), 16.0 - 4.0 - 0.25, 1e-4);
    expectWinding(m, rot * glm::vec3(0, 0, 1));
    // nothing inside the big hole
    glm::mat3 inv = glm::transpose(rot);
    for (size_t k = 0; k < m.mesh.tris.size(); k += 3) {
        glm::vec3 c = (m.mesh.p[m.mesh.tris[k]] + m.mesh.p[m.mesh.tris[k + 1]] +
                       m.mesh.p[m.mesh.tris[k + 2]]) / 3.0f;
        glm::vec3 l = inv * (c - glm::vec3(5, -2, 1));
        EXPECT_FALSE(l.x > 1.001f && l.x < 2.999f && l.y > 1.001f && l.y < 2.999f);
    }
}

TEST(Polygons, DuplicateAndCollinearPoints) {
    std::vector<glm::vec3> p = {{0, 0, 0}, {0.5f, 0, 0}, {0.5f, 0, 0}, {1, 0, 0}, {1, 0.5f, 0},
                                {1, 1, 0}, {0, 1, 0}, {0, 1, 0}, {0, 0.25f, 0}, {0, 0, 0}};
    SurfaceMesh m;
    ASSERT_TRUE(tessellateGeneralPolygon({int(p.size())}, p, m));
    test::expectWellFormed(m);
    EXPECT_NEAR(meshArea(m.mesh), 1.0, 1e-6);
}

TEST(Polygons, DegenerateInputGivesNoTriangles) {
    SurfaceMesh m;
    ASSERT_TRUE(tessellateGeneralPolygon({4}, {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {3, 3, 3}}, m));
    EXPECT_TRUE(m.mesh.tris.empty());
    ASSERT_TRUE(tessellateGeneralPolygon({2}, {{0, 0, 0}, {1, 0, 0}}, m));
    EXPECT_TRUE(m.mesh.tris.empty());
    ASSERT_TRUE(tessellateGeneralPolygon({3}, {{1, 1, 1}, {1, 1, 1}, {1, 1, 1}}, m));
    EXPECT_TRUE(m.mesh.tris.empty());
    // a hole that is all collinear is ignored
    SurfaceMesh h;
    ASSERT_TRUE(tessellateGeneralPolygon(
        {4, 3}, {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}, {0.5f, 1, 0}, {1, 1, 0}, {1.5f, 1, 0}}, h));
    EXPECT_NEAR(meshArea(h.mesh), 4.0, 1e-5);
}

TEST(Polygons, PointsGeneralPolygonsSharedVertices) {
    // two unit squares sharing an edge; the second has a triangular hole
    std::vector<glm::vec3> P = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}, {1, 1, 0}, {2, 1, 0},
                                {1.2f, 0.2f, 0}, {1.8f, 0.2f, 0}, {1.5f, 0.8f, 0}};
    SurfaceMesh m;
    ASSERT_TRUE(tessellatePointsGeneralPolygons({1, 2}, {4, 4, 3},
                                                {0, 1, 4, 3, 1, 2, 5, 4, 6, 7, 8}, P, m));
    test::expectWellFormed(m);
    EXPECT_EQ(m.mesh.p.size(), P.size());
    EXPECT_NEAR(meshArea(m.mesh), 2.0 - 0.5 * 0.6 * 0.6, 1e-5);
    EXPECT_EQ(m.faceIndex.front(), 0);
    EXPECT_EQ(m.faceIndex.back(), 1);
    EXPECT_EQ(std::count(m.faceIndex.begin(), m.faceIndex.end(), 0), 2);
}

TEST(Polygons, RejectsBadInput) {
    std::string err;
    SurfaceMesh m;
    EXPECT_FALSE(tessellateGeneralPolygon({5}, {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}}, m, &err));
    EXPECT_FALSE(err.empty());
    std::vector<glm::vec3> P = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}};
    EXPECT_FALSE(tessellatePointsGeneralPolygons({1}, {3}, {0, 1, 7}, P, m, &err));
    EXPECT_FALSE(tessellatePointsGeneralPolygons({2}, {3}, {0, 1, 2}, P, m, &err));
    EXPECT_FALSE(tessellatePointsGeneralPolygons({1}, {4}, {0, 1, 2}, P, m, &err));
    EXPECT_FALSE(tessellateGeneralPolygon({3}, {{0, 0, 0}, {NAN, 0, 0}, {1, 1, 0}}, m, &err));
    EXPECT_TRUE(m.mesh.p.empty());
}
