// patches_test.cpp: bilinear/bicubic patches and patch meshes: corner and interior
// reproduction, periodic closure, patch counts, Pz/Pw, bad input.
#include <cmath>

#include <gtest/gtest.h>

#include "host/scene/tessellate_patches.h"
#include "test_util.h"

using namespace rd;

namespace {
std::vector<float> flatten(const std::vector<glm::vec3>& v) {
    std::vector<float> f;
    for (auto& p : v) f.insert(f.end(), {p.x, p.y, p.z});
    return f;
}
void expectVec(glm::vec3 a, glm::vec3 b, float tol = 1e-5f) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}
std::vector<glm::vec3> bumpyGrid() {
    std::vector<glm::vec3> cp;
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i)
            cp.emplace_back(float(i), float(j), float((i * 7 + j * 3) % 5) * 0.25f);
    return cp;
}
}  // namespace

TEST(Patches, BezierCornersAndCentre) {
    auto cp = bumpyGrid();
    SurfaceMesh m;
    ASSERT_TRUE(tessellatePatch("bicubic", PositionKind::P, flatten(cp), bezierBasis(),
                                bezierBasis(), 2, 2, m));
    test::expectWellFormed(m);
    ASSERT_EQ(m.mesh.p.size(), 9u);
    expectVec(m.mesh.p[0], cp[0]);
    expectVec(m.mesh.p[2], cp[3]);
    expectVec(m.mesh.p[6], cp[12]);
    expectVec(m.mesh.p[8], cp[15]);
    const float b[4] = {1 / 8.f, 3 / 8.f, 3 / 8.f, 1 / 8.f};
    glm::vec3 c(0.0f);
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) c += b[i] * b[j] * cp[j * 4 + i];
    expectVec(m.mesh.p[4], c);
    EXPECT_FLOAT_EQ(m.st[4].x, 0.5f);
    EXPECT_FLOAT_EQ(m.st[4].y, 0.5f);
    for (int f : m.faceIndex) EXPECT_EQ(f, 0);
}

TEST(Patches, BilinearAndHeightField) {
    std::vector<glm::vec3> cp = {{0, 0, 0}, {2, 0, 0}, {0, 2, 1}, {2, 2, 1}};
    SurfaceMesh m;
    ASSERT_TRUE(tessellatePatch("bilinear", PositionKind::P, flatten(cp), bezierBasis(),
                                bezierBasis(), 4, 4, m));
    test::expectWellFormed(m);
    expectVec(m.mesh.p[12], glm::vec3(1.0f, 1.0f, 0.5f));
    // +z-ish normal: dPdu = (2,0,0), dPdv = (0,2,1)
    expectVec(m.mesh.n[0], glm::normalize(glm::vec3(0, -2, 4)));
    SurfaceMesh h;
    ASSERT_TRUE(tessellatePatch("bilinear", PositionKind::Pz, {0.f, 1.f, 2.f, 3.f},
                                bezierBasis(), bezierBasis(), 1, 1, h));
    ASSERT_EQ(h.mesh.p.size(), 4u);
    expectVec(h.mesh.p[0], {0, 0, 0});
    expectVec(h.mesh.p[1], {1, 0, 1});
    expectVec(h.mesh.p[2], {0, 1, 2});
    expectVec(h.mesh.p[3], {1, 1, 3});
}

TEST(Patches, HomogeneousPw) {
    auto cp = bumpyGrid();
    std::vector<float> pw;
    for (size_t k = 0; k < cp.size(); ++k) {
        float w = 1.0f + float(k % 3);
        pw.insert(pw.end(), {cp[k].x * w, cp[k].y * w, cp[k].z * w, w});
    }
    SurfaceMesh m;
    ASSERT_TRUE(tessellatePatch("bicubic", PositionKind::Pw, pw, bezierBasis(), bezierBasis(),
                                6, 6, m));
    test::expectWellFormed(m);
    expectVec(m.mesh.p[0], cp[0]);
    expectVec(m.mesh.p[6], cp[3]);
    expectVec(m.mesh.p[48], cp[15]);
}

TEST(Patches, PatchCountFormula) {
    EXPECT_EQ(patchCount(true, 4, false, 3), 1);
    EXPECT_EQ(patchCount(true, 7, false, 3), 2);
    EXPECT_EQ(patchCount(true, 13, false, 3), 4);
    EXPECT_EQ(patchCount(true, 6, false, 3), -1);
    EXPECT_EQ(patchCount(true, 6, false, 1), 3);
    EXPECT_EQ(patchCount(true, 8, true, 1), 8);
    EXPECT_EQ(patchCount(true, 6, true, 3), 2);
    EXPECT_EQ(patchCount(true, 8, true, 3), -1);
    EXPECT_EQ(patchCount(true, 6, false, 2), 2);
    EXPECT_EQ(patchCount(true, 3, false, 1), -1);
    EXPECT_EQ(patchCount(false, 5, false, 3), 4);
    EXPECT_EQ(patchCount(false, 5, true, 3), 5);
    EXPECT_EQ(patchCount(false, 1, false, 3), -1);
    EXPECT_EQ(patchCount(true, 4, false, 0), -1);

    PatchMeshInput in;
    in.bicubic = true;
    in.nu = 7;
    in.nv = 6;
    in.vbasis = bSplineBasis();
    in.positions.resize(7 * 6 * 3);
    for (int j = 0; j < 6; ++j)
        for (int i = 0; i < 7; ++i) {
            float* f = &in.positions[(j * 7 + i) * 3];
            f[0] = float(i), f[1] = float(j), f[2] = 0.1f * float(i * j % 4);
        }
    SurfaceMesh m;
    ASSERT_TRUE(tessellatePatchMesh(in, 3, 3, m));
    test::expectWellFormed(m);
    EXPECT_EQ(m.mesh.p.size(), size_t(2 * 3 * 16));
    EXPECT_EQ(m.faceIndex.size(), size_t(2 * 3 * 9 * 2));
    EXPECT_EQ(m.faceIndex.back(), 5);
}

TEST(Patches, PeriodicBSplineTubeClosesWithoutSeams) {
    const int nu = 8, nv = 5;
    PatchMeshInput in;
    in.bicubic = true;
    in.nu = nu;
    in.nv = nv;
    in.uperiodic = true;
    in.ubasis = in.vbasis = bSplineBasis();
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) {
            float a = 2.0f * float(M_PI) * float(i) / nu;
            in.positions.insert(in.positions.end(), {std::cos(a), std::sin(a), float(j)});
        }
    SurfaceMesh m;
    const int seg = 4;
    ASSERT_TRUE(tessellatePatchMesh(in, seg, seg, m));
    test::expectWellFormed(m);
    int npu = nu, npv = 2;
    ASSERT_EQ(m.mesh.p.size(), size_t(npu * npv * (seg + 1) * (seg + 1)));
    auto vert = [&](int pu, int pv, int i, int j) {
        return ((pv * npu + pu) * (seg + 1) + j) * (seg + 1) + i;
    };
    for (int pv = 0; pv < npv; ++pv)
        for (int pu = 0; pu < npu; ++pu)
            for (int j = 0; j <= seg; ++j) {
                int a = vert(pu, pv, seg, j), b = vert((pu + 1) % npu, pv, 0, j);
                expectVec(m.mesh.p[a], m.mesh.p[b]);
                EXPECT_GT(glm::dot(m.mesh.n[a], m.mesh.n[b]), 0.99999f);
            }
    // rotationally symmetric: every vertex at the same distance from the axis per row
    for (size_t k = 0; k < m.mesh.p.size(); ++k) {
        glm::vec3 p = m.mesh.p[k];
        EXPECT_NEAR(std::hypot(p.x, p.y), std::hypot(m.mesh.p[0].x, m.mesh.p[0].y), 0.03f);
        EXPECT_GT(glm::dot(m.mesh.n[k], glm::vec3(p.x, p.y, 0.0f)), 0.0f);  // outward
    }
    EXPECT_NEAR(m.st.back().x, 1.0f, 1e-6f);
}

TEST(Patches, CatmullRomInterpolatesAndHermite) {
    PatchMeshInput in;
    in.bicubic = true;
    in.nu = 5;
    in.nv = 4;
    in.ubasis = catmullRomBasis();
    in.vbasis = catmullRomBasis();
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 5; ++i)
            in.positions.insert(in.positions.end(), {float(i), float(j), float((i + j) % 2)});
    SurfaceMesh m;
    ASSERT_TRUE(tessellatePatchMesh(in, 2, 2, m));
    ASSERT_EQ(m.mesh.p.size(), size_t(2 * 9));
    expectVec(m.mesh.p[0], {1, 1, 0});
    expectVec(m.mesh.p[2], {2, 1, 1});
    expectVec(m.mesh.p[9 + 2], {3, 1, 0});
    expectVec(m.mesh.p[9 + 8], {3, 2, 1});
    CubicBasis h;
    ASSERT_TRUE(basisByName("hermite", h));
    float w[4];
    basisWeights(h, 0.0f, w);
    EXPECT_FLOAT_EQ(w[0], 1.0f);
    basisWeights(h, 1.0f, w);
    EXPECT_FLOAT_EQ(w[2], 1.0f);
    float dw[4];
    basisWeights(h, 0.0f, w, dw);
    EXPECT_FLOAT_EQ(dw[1], 1.0f);  // tangent weight
}

TEST(Patches, ExplicitBasisAndBadInput) {
    float bez[16] = {-1, 3, -3, 1, 3, -6, 3, 0, -3, 3, 0, 0, 1, 0, 0, 0};
    CubicBasis b;
    ASSERT_TRUE(basisFromMatrix(bez, 3, b));
    std::string err;
    EXPECT_FALSE(basisFromMatrix(bez, 0, b, &err));
    CubicBasis x;
    EXPECT_FALSE(basisByName("nurbs", x));
    SurfaceMesh m;
    EXPECT_FALSE(tessellatePatch("bicubic", PositionKind::P, std::vector<float>(15 * 3),
                                 bezierBasis(), bezierBasis(), 4, 4, m, &err));
    EXPECT_FALSE(err.empty());
    EXPECT_FALSE(tessellatePatch("trilinear", PositionKind::P, std::vector<float>(12),
                                 bezierBasis(), bezierBasis(), 4, 4, m, &err));
    PatchMeshInput in;
    in.bicubic = true;
    in.nu = 6;
    in.nv = 4;
    in.positions.resize(6 * 4 * 3);
    EXPECT_FALSE(tessellatePatchMesh(in, 4, 4, m, &err));  // (6-4) % 3 != 0
    EXPECT_TRUE(m.mesh.p.empty());
    std::vector<float> nanPts(16 * 3, 0.0f);
    nanPts[5] = NAN;
    EXPECT_FALSE(tessellatePatch("bicubic", PositionKind::P, nanPts, bezierBasis(),
                                 bezierBasis(), 4, 4, m, &err));
    // density capped
    std::vector<float> ok(16 * 3, 0.0f);
    EXPECT_FALSE(tessellatePatch("bicubic", PositionKind::P, ok, bezierBasis(), bezierBasis(),
                                 100000, 100000, m, &err));
}
