// nurbs_test.cpp: NuPatch evaluation (planes, rational sphere of revolution), knot
// validation and TrimCurve trimming.
#include <cmath>

#include <gtest/gtest.h>

#include "host/scene/tessellate_nurbs.h"
#include "test_util.h"

using namespace rd;

namespace {
const float kS = float(M_SQRT1_2);

// Unit square [0,1]^2 in z=0 as a bilinear (order 2) NuPatch.
NuPatchInput unitPlane() {
    NuPatchInput in;
    in.nu = in.nv = 2;
    in.uorder = in.vorder = 2;
    in.uknot = in.vknot = {0, 0, 1, 1};
    in.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
    return in;
}

// Full circle: 9-point rational quadratic, as (x, y, w) with x,y not premultiplied.
const float kCircle[9][3] = {{1, 0, 1},  {1, 1, kS},  {0, 1, 1},   {-1, 1, kS}, {-1, 0, 1},
                             {-1, -1, kS}, {0, -1, 1}, {1, -1, kS}, {1, 0, 1}};
const std::vector<float> kCircleKnots = {0, 0, 0, .25f, .25f, .5f, .5f, .75f, .75f, 1, 1, 1};
}  // namespace

TEST(Nurbs, UntrimmedPlane) {
    NuPatchInput in = unitPlane();
    SurfaceMesh m;
    ASSERT_TRUE(tessellateNuPatch(in, 8, 8, nullptr, m));
    test::expectWellFormed(m);
    EXPECT_NEAR(meshArea(m.mesh), 1.0, 1e-6);
    for (size_t i = 0; i < m.mesh.p.size(); ++i) {
        EXPECT_NEAR(m.mesh.p[i].x, m.st[i].x, 1e-6f);
        EXPECT_NEAR(m.mesh.p[i].y, m.st[i].y, 1e-6f);
        EXPECT_NEAR(m.mesh.n[i].z, 1.0f, 1e-6f);
    }
    // A cubic plane over two spans with umin/umax inside the range.
    NuPatchInput c;
    c.nu = 5;
    c.uorder = 4;
    c.uknot = {0, 0, 0, 0, 1, 2, 2, 2, 2};
    c.nv = 2;
    c.vorder = 2;
    c.vknot = {0, 0, 1, 1};
    c.umin = 0.5f;
    c.umax = 2.0f;
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 5; ++i) c.positions.insert(c.positions.end(), {float(i), float(j), 0});
    SurfaceMesh cm;
    ASSERT_TRUE(tessellateNuPatch(c, 12, 2, nullptr, cm));
    test::expectWellFormed(cm);
    EXPECT_NEAR(cm.mesh.p.back().x, 4.0f, 1e-5f);  // clamped end interpolates
    EXPECT_NEAR(cm.st.front().x, 0.5f, 1e-6f);
    EXPECT_EQ(cm.faceIndex.front(), 0);
    EXPECT_EQ(cm.faceIndex.back(), 1);  // second knot span
}

TEST(Nurbs, RationalSphereOfRevolutionIsExact) {
    // Profile: semicircle in (rho, z) from the south pole to the north pole.
    const float prof[5][3] = {{0, -1, 1}, {1, -1, kS}, {1, 0, 1}, {1, 1, kS}, {0, 1, 1}};
    NuPatchInput in;
    in.nu = 9;
    in.uorder = 3;
    in.uknot = kCircleKnots;
    in.nv = 5;
    in.vorder = 3;
    in.vknot = {0, 0, 0, .5f, .5f, 1, 1, 1};
    in.rational = true;
    for (int j = 0; j < 5; ++j)
        for (int i = 0; i < 9; ++i) {
            float w = kCircle[i][2] * prof[j][2];
            glm::vec3 p(prof[j][0] * kCircle[i][0], prof[j][0] * kCircle[i][1], prof[j][1]);
            in.positions.insert(in.positions.end(), {p.x * w, p.y * w, p.z * w, w});
        }
    SurfaceMesh m;
    ASSERT_TRUE(tessellateNuPatch(in, 64, 32, nullptr, m));
    test::expectWellFormed(m);
    double maxErr = 0.0;
    for (size_t i = 0; i < m.mesh.p.size(); ++i) {
        maxErr = std::max(maxErr, std::fabs(double(glm::length(m.mesh.p[i])) - 1.0));
        EXPECT_GT(glm::dot(m.mesh.n[i], m.mesh.p[i]), 0.99f) << i;  // outward
    }
    EXPECT_LT(maxErr, 1e-5);
    EXPECT_NEAR(meshArea(m.mesh), 4.0 * M_PI, 0.01 * 4.0 * M_PI);
}

TEST(Nurbs, RejectsBadKnotsAndSizes) {
    std::string err;
    NuPatchInput in = unitPlane();
    in.uknot = {0, 0, 1};  // wrong length
    SurfaceMesh m;
    EXPECT_FALSE(tessellateNuPatch(in, 4, 4, nullptr, m, &err));
    EXPECT_FALSE(err.empty());
    in = unitPlane();
    in.vknot = {0, 1, 0, 1};  // decreasing
    EXPECT_FALSE(tessellateNuPatch(in, 4, 4, nullptr, m, &err));
    in = unitPlane();
    in.uorder = 0;
    EXPECT_FALSE(tessellateNuPatch(in, 4, 4, nullptr, m, &err));
    in = unitPlane();
    in.positions.pop_back();
    EXPECT_FALSE(tessellateNuPatch(in, 4, 4, nullptr, m, &err));
    in = unitPlane();
    in.umin = in.umax = 0.5f;
    EXPECT_FALSE(tessellateNuPatch(in, 4, 4, nullptr, m, &err));
    EXPECT_TRUE(m.mesh.p.empty());
    EXPECT_TRUE(validateKnots(3, 3, {0, 0, 0, 1, 1, 1}, &err));
    EXPECT_FALSE(validateKnots(3, 3, {0, 0, 0, 0, 0, 0}, &err));
    TrimCurves t;
    t.ncurves = {1};
    t.order = {2};
    t.n = {3};
    t.knot = {0, 0, 1, 1};  // should be 5 knots
    t.min = {0};
    t.max = {1};
    t.u = t.v = t.w = {0, 1, 0};
    EXPECT_FALSE(validateTrimCurves(t, &err));
    EXPECT_FALSE(tessellateNuPatch(unitPlane(), 4, 4, &t, m, &err));
}

TEST(Nurbs, TrimmedSquareWithCircularHole) {
    const float cx = 0.5f, cy = 0.5f, r = 0.3f;
    TrimCurves t;
    // loop 1: the square boundary as one linear curve (order 2, 5 points)
    t.ncurves = {1, 1};
    t.order = {2, 3};
    t.n = {5, 9};
    t.knot = {0, 0, 1, 2, 3, 4, 4};
    t.min = {0, 0};
    t.max = {4, 1};
    t.u = {0, 1, 1, 0, 0};
    t.v = {0, 0, 1, 1, 0};
    t.w = {1, 1, 1, 1, 1};
    // loop 2: the circle, clockwise, homogeneous (u w, v w, w)
    t.knot.insert(t.knot.end(), kCircleKnots.begin(), kCircleKnots.end());
    for (int i = 0; i < 9; ++i) {
        float w = kCircle[i][2];
        t.u.push_back((cx + r * kCircle[i][0]) * w);
        t.v.push_back((cy - r * kCircle[i][1]) * w);
        t.w.push_back(w);
    }
    std::vector<std::vector<glm::vec2>> loops;
    ASSERT_TRUE(trimLoopPolylines(t, 16, loops, nullptr));
    ASSERT_EQ(loops.size(), 2u);
    for (auto& p : loops[1]) EXPECT_NEAR(glm::length(p - glm::vec2(cx, cy)), r, 1e-5f);
    EXPECT_TRUE(insideLoops(loops, {0.1f, 0.1f}));
    EXPECT_FALSE(insideLoops(loops, {0.5f, 0.5f}));

    SurfaceMesh m;
    ASSERT_TRUE(tessellateNuPatch(unitPlane(), 32, 32, &t, m));
    test::expectWellFormed(m);
    double exact = 1.0 - M_PI * r * r;
    EXPECT_NEAR(meshArea(m.mesh), exact, 0.02 * exact);
    for (size_t k = 0; k < m.mesh.tris.size(); k += 3) {
        glm::vec2 c = (m.st[m.mesh.tris[k]] + m.st[m.mesh.tris[k + 1]] + m.st[m.mesh.tris[k + 2]]) / 3.0f;
        EXPECT_GT(glm::length(c - glm::vec2(cx, cy)), r - 0.02f);
    }
    // The opposite sense keeps only the disk.
    SurfaceMesh d;
    ASSERT_TRUE(tessellateNuPatch(unitPlane(), 64, 64, &t, d, nullptr, false));
    EXPECT_NEAR(meshArea(d.mesh), M_PI * r * r, 0.02 * M_PI * r * r);
}
