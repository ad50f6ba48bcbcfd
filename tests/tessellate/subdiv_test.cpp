// subdiv_test.cpp: SubdivisionMesh through OpenSubdiv: Catmull-Clark cube limit surface
// (inside the cage, symmetric, outward normals), holes, sharp creases, facevarying
// values and their seams; Loop's limit on an octahedron, the bilinear cube; bad input.
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

// A flat 2x2 grid of unit quads (ridge(2), flattened), a value per face-vertex such as
// an asset's texture coordinates: continuous (s = x / 2), or with a seam down the middle
// edge x = 1 (the left faces' s in [0, 0.4], the right faces' in [0.6, 1]), as a UV
// layout cuts a mesh. Continuous, no vertex is split and s = x / 2 on the faces' edges
// (linear in each face's parameters, which meet the cage's lines there). With the seam,
// the nine vertices on x = 1 come out twice, one a side: each triangle's s lies in its
// own face's range, and the seam's points carry 0.4 on the left and 0.6 on the right. A
// vertex value follows its vertex onto both sides, and a second facevarying channel
// (continuous, x + 10 y) is exact on the cage's lines.
TEST(Subdiv, FacevaryingValuesSplitVerticesAtSeams) {
    SubdivInput in = ridge(2);
    for (glm::vec3& p : in.P) p.z = 0.0f;
    auto sOf = [&](bool seam) {
        std::vector<glm::vec3> out;
        for (size_t c = 0; c < in.vertices.size(); ++c) {
            const glm::vec3 p = in.P[size_t(in.vertices[c])];
            const bool left = in.vertices[c - c % 4] % 3 == 0;  // the face's first corner
            float s = p.x / 2.0f;
            if (seam) s = left ? 0.4f * p.x : 0.6f + 0.4f * (p.x - 1.0f);
            out.emplace_back(s, p.y / 2.0f, 0.0f);
        }
        return out;
    };
    std::string err;
    in.faceVaryingValues = {sOf(false)};
    SurfaceMesh smooth;
    std::vector<std::vector<glm::vec3>> smoothValues;
    ASSERT_TRUE(tessellateSubdivisionMesh(in, 2, smooth, &err, &smoothValues)) << err;
    in.vertexValues = {in.P};  // a vertex value: the control vertex's position
    std::vector<glm::vec3> xy;
    for (int v : in.vertices) {
        const glm::vec3 p = in.P[size_t(v)];
        xy.emplace_back(p.x + 10.0f * p.y, 0.0f, 0.0f);
    }
    in.faceVaryingValues = {sOf(true), xy};
    SurfaceMesh seam;
    std::vector<std::vector<glm::vec3>> values;  // P, then s, then x + 10 y
    ASSERT_TRUE(tessellateSubdivisionMesh(in, 2, seam, &err, &values)) << err;
    ASSERT_EQ(smoothValues.size(), 1u);
    ASSERT_EQ(smoothValues[0].size(), smooth.mesh.p.size());
    ASSERT_EQ(values.size(), 3u);
    for (const std::vector<glm::vec3>& v : values) ASSERT_EQ(v.size(), seam.mesh.p.size());
    // 9 x 9 vertices at level 2, the 9 on x = 1 twice with the seam
    EXPECT_EQ(smooth.mesh.p.size(), 81u);
    EXPECT_EQ(seam.mesh.p.size(), 90u);
    for (size_t i = 0; i < smooth.mesh.p.size(); ++i) {
        const glm::vec3 p = smooth.mesh.p[i];
        const float s = smoothValues[0][i].x;
        if (std::fabs(p.x - std::round(p.x)) < 1e-5f) {  // on a face's edge
            EXPECT_NEAR(s, p.x / 2.0f, 1e-5f) << p.x << "," << p.y;
        }
        EXPECT_GE(s, -1e-6f);
        EXPECT_LE(s, 1.0f + 1e-6f);
    }
    for (size_t v = 0; v < seam.mesh.p.size(); ++v) {  // on the cage's lines: exact
        const glm::vec3 p = seam.mesh.p[v];
        if (std::fabs(p.x - std::round(p.x)) < 1e-5f && std::fabs(p.y - std::round(p.y)) < 1e-5f) {
            EXPECT_NEAR(values[2][v].x, p.x + 10.0f * p.y, 1e-4f) << p.x << "," << p.y;
        }
    }
    int onSeam[2] = {0, 0};
    for (size_t k = 0; k < seam.faceIndex.size(); ++k) {
        const bool left = seam.faceIndex[k] % 2 == 0;
        for (int c = 0; c < 3; ++c) {
            const size_t v = size_t(seam.mesh.tris[3 * k + size_t(c)]);
            const float sv = values[1][v].x;
            if (left) {
                EXPECT_LE(sv, 0.4f + 1e-5f);
            } else {
                EXPECT_GE(sv, 0.6f - 1e-5f);
            }
            if (std::fabs(seam.mesh.p[v].x - 1.0f) < 1e-5f) {
                EXPECT_NEAR(sv, left ? 0.4f : 0.6f, 1e-5f);
                ++onSeam[left ? 0 : 1];
            }
            // the vertex value is the limit of the positions, as P is
            EXPECT_NEAR(glm::length(values[0][v] - seam.mesh.p[v]), 0.0f, 1e-4f);
        }
    }
    EXPECT_GT(onSeam[0], 0);
    EXPECT_GT(onSeam[1], 0);
}

// Loop's scheme on the octahedron with vertices on the unit axes (every vertex of
// valence 4): a control vertex's limit is (1 - n g) v + g (its neighbours' sum) with
// g = 1 / (3 / (8 b) + n), b = (5/8 - (3/8 + cos(2 pi / n) / 4)^2) / n (Loop 1987), and
// its neighbours sum to 0: at n = 4 the surface meets the axes at 1 - 4 g = 0.43636
// (Catmull-Clark's treatment of the same cage would need quads). Each triangle is split
// in 4 a level, every point lies inside the cage, and the normals point out.
TEST(Subdiv, LoopOctahedronMeetsTheAxesAtItsLimitMask) {
    SubdivInput in;
    in.scheme = "loop";
    in.P = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    in.nvertices.assign(8, 3);
    for (int a : {0, 1})
        for (int b : {2, 3})
            for (int c : {4, 5}) {
                // wound counter-clockwise seen from outside: (x, y, z) signs' parity
                const bool flip = ((a == 1) + (b == 3) + (c == 5)) % 2 == 1;
                in.vertices.insert(in.vertices.end(), {a, flip ? c : b, flip ? b : c});
            }
    SurfaceMesh m;
    ASSERT_TRUE(tessellateSubdivisionMesh(in, 3, m));
    test::expectWellFormed(m);
    EXPECT_EQ(m.mesh.tris.size() / 3, size_t(8 * 64));
    const double n = 4,
                 beta = (5.0 / 8 - std::pow(3.0 / 8 + std::cos(2 * M_PI / n) / 4, 2)) / n;
    const double limit = 1 - n / (3 / (8 * beta) + n);
    double atAxis = 0;
    for (size_t i = 0; i < m.mesh.p.size(); ++i) {
        const glm::vec3 p = m.mesh.p[i];
        EXPECT_LT(std::fabs(p.x) + std::fabs(p.y) + std::fabs(p.z), 1.0f + 1e-5f);
        EXPECT_GT(glm::dot(m.mesh.n[i], p), 0.0f);
        atAxis = std::max(atAxis, double(p.x));
    }
    EXPECT_NEAR(limit, 0.43636, 1e-5);
    EXPECT_NEAR(atAxis, limit, 1e-5);
    for (int f : m.faceIndex) EXPECT_TRUE(f >= 0 && f < 8);
}

// The bilinear scheme keeps the cage's faces: the cube refined stays the cube (every
// point on a face, every corner kept) and is shaded faceted (no vertex normals); each
// quad splits into 4 a level, 8 triangles a face at level 1.
TEST(Subdiv, BilinearCubeStaysTheCube) {
    SubdivInput in = cube();
    in.scheme = "bilinear";
    SurfaceMesh m;
    ASSERT_TRUE(tessellateSubdivisionMesh(in, 2, m));
    EXPECT_EQ(m.mesh.tris.size() / 3, size_t(6 * 16 * 2));
    EXPECT_TRUE(m.mesh.n.empty());
    int corners = 0;
    for (const glm::vec3& p : m.mesh.p) {
        const glm::vec3 a = glm::abs(p);
        EXPECT_NEAR(std::max(a.x, std::max(a.y, a.z)), 1.0f, 1e-6f);
        corners += a.x > 0.999999f && a.y > 0.999999f && a.z > 0.999999f;
    }
    EXPECT_EQ(corners, 8);
    ASSERT_EQ(m.faceIndex.size(), size_t(6 * 16 * 2));
    EXPECT_EQ(m.faceIndex.front(), 0);
    EXPECT_EQ(m.faceIndex.back(), 5);
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
    in.scheme = "loop";  // (Loop subdivides triangles, and the cube's faces are quads)
    EXPECT_FALSE(tessellateSubdivisionMesh(in, 2, m, &err));
    EXPECT_NE(err.find("face 0 has 4 vertices"), std::string::npos) << err;
    in.scheme = "doo-sabin";
    EXPECT_FALSE(tessellateSubdivisionMesh(in, 2, m, &err));
    EXPECT_NE(err.find("\"doo-sabin\" is not known"), std::string::npos) << err;
    in = cube();
    in.tags = {"hole"};
    in.nargs = {1, 0};
    in.intargs = {6};
    EXPECT_FALSE(tessellateSubdivisionMesh(in, 2, m, &err));
    in = cube();  // facevarying values: one a face-vertex (24), not one a vertex (8)
    in.faceVaryingValues.assign(1, std::vector<glm::vec3>(8));
    EXPECT_FALSE(tessellateSubdivisionMesh(in, 2, m, &err));
    EXPECT_NE(err.find("facevarying values"), std::string::npos) << err;
    EXPECT_TRUE(m.mesh.p.empty());
}
