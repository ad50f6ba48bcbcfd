// subdiv_test.cpp: Catmull-Clark SubdivisionMesh through OpenSubdiv: cube limit surface
// (inside the cage, symmetric, outward normals), holes, sharp creases, bad input.
#include <cmath>

#include <gtest/gtest.h>

#include "host/scene/tessellate_subdiv.h"
#include "test_util.h"

using namespace rd;

namespace {
SubdivInput cube() {
    SubdivInput in;
    for (int i = 0; i < 8; ++i)
        in.P.emplace_back(i & 1 ? 1.0f : -1.0f, i & 2 ? 1.0f : -1.0f, i & 4 ? 1.0f : -1.0f);
    // counter-clockwise seen from outside
    in.nvertices = {4, 4, 4, 4, 4, 4};
    in.vertices = {0, 2, 3, 1,  4, 5, 7, 6,  0, 1, 5, 4,
                   2, 6, 7, 3,  0, 4, 6, 2,  1, 3, 7, 5};
    return in;
}

// (nx+1) x 3 vertex grid in the xy plane, row y=1 raised to z=1.
SubdivInput ridge(int nx) {
    SubdivInput in;
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i <= nx; ++i) in.P.emplace_back(float(i), float(j), j == 1 ? 1.0f : 0.0f);
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < nx; ++i) {
            int a = j * (nx + 1) + i;
            in.nvertices.push_back(4);
            in.vertices.insert(in.vertices.end(), {a, a + 1, a + nx + 2, a + nx + 1});
        }
    in.tags = {"interpolateboundary"};
    in.nargs = {0, 0};
    return in;
}
}  // namespace

#ifdef RD_HAVE_OPENSUBDIV

TEST(Subdiv, CubeLimitInsideCageSymmetricOutward) {
    SurfaceMesh m;
    ASSERT_TRUE(tessellateSubdivisionMesh(cube(), 4, m));
    test::expectWellFormed(m);
    EXPECT_EQ(m.mesh.tris.size() / 3, size_t(6 * 256 * 2));
    glm::vec3 lo(1e9f), hi(-1e9f);
    for (size_t i = 0; i < m.mesh.p.size(); ++i) {
        glm::vec3 p = m.mesh.p[i];
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
        EXPECT_LT(glm::length(p), std::sqrt(3.0f) - 0.1f);
        EXPECT_GT(glm::dot(m.mesh.n[i], p), 0.0f);
    }
    for (int a = 0; a < 3; ++a) {
        EXPECT_LT(hi[a], 1.0f);
        EXPECT_NEAR(lo[a], -hi[a], 1e-5f);
        EXPECT_NEAR(hi[a], hi[0], 1e-5f);
    }
    // Face centre limit: after one step the face point (0,0,1) is regular, with edge
    // points at z = 3/4 and corner points at z = 5/9; the limit mask (16, 4x4, 1x4)/36
    // gives z = (16 + 12 + 20/9) / 36 = 68/81.
    EXPECT_NEAR(hi[2], 68.0f / 81.0f, 1e-5f);
    for (int f : m.faceIndex) EXPECT_TRUE(f >= 0 && f < 6);
}

TEST(Subdiv, HoleRemovesFaces) {
    SubdivInput in = cube();
    in.tags = {"hole"};
    in.nargs = {1, 0};
    in.intargs = {2};
    SurfaceMesh m;
    ASSERT_TRUE(tessellateSubdivisionMesh(in, 3, m));
    test::expectWellFormed(m);
    EXPECT_EQ(m.mesh.tris.size() / 3, size_t(5 * 64 * 2));
    for (int f : m.faceIndex) EXPECT_NE(f, 2);
}

TEST(Subdiv, SharpCreaseKeepsEdgeStraight) {
    SurfaceMesh smooth;
    ASSERT_TRUE(tessellateSubdivisionMesh(ridge(4), 4, smooth));
    float smoothMax = -1.0f;
    for (auto& p : smooth.mesh.p) smoothMax = std::max(smoothMax, p.z);
    EXPECT_LT(smoothMax, 0.9f);

    SubdivInput in = ridge(4);
    in.tags.push_back("crease");
    in.nargs.insert(in.nargs.end(), {5, 1});
    in.intargs = {5, 6, 7, 8, 9};
    in.floatargs = {10.0f};
    SurfaceMesh m;
    ASSERT_TRUE(tessellateSubdivisionMesh(in, 4, m));
    test::expectWellFormed(m, false);  // normals across a sharp crease are one-sided
    int onCrease = 0;
    for (auto& p : m.mesh.p)
        if (std::fabs(p.y - 1.0f) < 1e-5f) {
            ++onCrease;
            EXPECT_NEAR(p.z, 1.0f, 1e-5f);
        }
    EXPECT_GE(onCrease, 4 * 16 + 1);
}

TEST(Subdiv, CornerAndInterpolateBoundaryPinCorners) {
    SubdivInput in = ridge(2);
    SurfaceMesh m;
    ASSERT_TRUE(tessellateSubdivisionMesh(in, 3, m));
    bool found = false;
    for (auto& p : m.mesh.p) found |= glm::length(p - glm::vec3(0, 0, 0)) < 1e-5f;
    EXPECT_TRUE(found) << "interpolateboundary keeps the cage corner";
    SubdivInput c = cube();
    c.tags = {"corner"};
    c.nargs = {1, 1};
    c.intargs = {7};
    c.floatargs = {10.0f};
    SurfaceMesh cm;
    ASSERT_TRUE(tessellateSubdivisionMesh(c, 3, cm));
    found = false;
    for (auto& p : cm.mesh.p) found |= glm::length(p - glm::vec3(1, 1, 1)) < 1e-4f;
    EXPECT_TRUE(found) << "a sharp corner is interpolated";
}

#endif  // RD_HAVE_OPENSUBDIV

TEST(Subdiv, RejectsBadInput) {
    std::string err;
    SurfaceMesh m;
    SubdivInput in = cube();
    in.vertices[3] = 8;
    EXPECT_FALSE(tessellateSubdivisionMesh(in, 2, m, &err));
    EXPECT_FALSE(err.empty());
    in = cube();
    in.nvertices.pop_back();
    EXPECT_FALSE(tessellateSubdivisionMesh(in, 2, m, &err));
    in = cube();
    in.tags = {"crease"};
    in.nargs = {2, 1};
    in.intargs = {0};
    EXPECT_FALSE(tessellateSubdivisionMesh(in, 2, m, &err));
    in = cube();
    in.scheme = "loop";
    EXPECT_FALSE(tessellateSubdivisionMesh(in, 2, m, &err));
    in = cube();
    in.tags = {"hole"};
    in.nargs = {1, 0};
    in.intargs = {6};
    EXPECT_FALSE(tessellateSubdivisionMesh(in, 2, m, &err));
    EXPECT_TRUE(m.mesh.p.empty());
}
