// quadrics_test.cpp: RI quadric tessellation: points on the analytic surface, areas
// converging to the closed forms, unit outward normals.
#include <cmath>
#include <tuple>

#include <gtest/gtest.h>

#include "host/scene/tessellate_quadrics.h"
#include "test_util.h"

using namespace rd;

namespace {
const double kPi = M_PI;

void expectAreaConverges(const std::function<SurfaceMesh(int)>& make, double exact) {
    double e32 = std::fabs(meshArea(make(32).mesh) - exact);
    double e128 = std::fabs(meshArea(make(128).mesh) - exact);
    EXPECT_LT(e128, 0.005 * exact) << "area not within 0.5% at density 128";
    EXPECT_LT(e128, e32 + 1e-6 * exact) << "area error does not shrink with density";
}
}  // namespace

TEST(Quadrics, CylinderOnSurfaceAndOutward) {
    SurfaceMesh m;
    ASSERT_TRUE(tessellateCylinder(2.0f, -1.0f, 3.0f, 270.0f, 48, 4, m));
    test::expectWellFormed(m);
    for (size_t i = 0; i < m.mesh.p.size(); ++i) {
        glm::vec3 p = m.mesh.p[i];
        EXPECT_NEAR(std::hypot(p.x, p.y), 2.0f, 1e-5f);
        EXPECT_GE(p.z, -1.0f - 1e-6f);
        EXPECT_LE(p.z, 3.0f + 1e-6f);
        glm::vec3 out = glm::normalize(glm::vec3(p.x, p.y, 0.0f));
        EXPECT_GT(glm::dot(m.mesh.n[i], out), 0.999f);
        // u = theta / thetamax
        float th = std::atan2(p.y, p.x);
        if (th < -1e-4f) th += 2.0f * float(kPi);
        EXPECT_NEAR(m.st[i].x, th / (1.5f * float(kPi)), 1e-4f);
    }
    EXPECT_EQ(m.mesh.p.size(), size_t(49 * 5));
    expectAreaConverges(
        [](int n) {
            SurfaceMesh s;
            tessellateCylinder(2.0f, -1.0f, 3.0f, 270.0f, n, 2, s);
            return s;
        },
        2.0 * 1.5 * kPi * 4.0);
}

TEST(Quadrics, NegativeThetamaxTurnsInwardNegativeRadiusMirrors) {
    // n = dPdu x dPdv literally: a negative thetamax reverses dPdu (inside out); for the
    // cylinder a negative radius mirrors the points through the axis and reverses dPdu,
    // so the normal still points away from the axis.
    for (auto [r, tm, sign] : {std::tuple{-1.0f, 360.0f, 1.0f}, std::tuple{1.0f, -360.0f, -1.0f}}) {
        SurfaceMesh m;
        ASSERT_TRUE(tessellateCylinder(r, 0.0f, 1.0f, tm, 16, 2, m));
        test::expectWellFormed(m);
        for (size_t i = 0; i < m.mesh.p.size(); ++i) {
            glm::vec3 p = m.mesh.p[i];
            EXPECT_GT(sign * glm::dot(m.mesh.n[i], glm::vec3(p.x, p.y, 0.0f)), 0.0f);
        }
    }
}

TEST(Quadrics, ConeSurfaceAreaAndApex) {
    float h = 2.0f, R = 1.5f;
    SurfaceMesh m;
    ASSERT_TRUE(tessellateCone(h, R, 360.0f, 64, 8, m));
    test::expectWellFormed(m);
    for (size_t i = 0; i < m.mesh.p.size(); ++i) {
        glm::vec3 p = m.mesh.p[i];
        EXPECT_NEAR(std::hypot(p.x, p.y), R * (1.0f - p.z / h), 1e-5f);
        EXPECT_GT(m.mesh.n[i].z, 0.0f);  // outward-and-up
    }
    expectAreaConverges(
        [&](int n) {
            SurfaceMesh s;
            tessellateCone(h, R, 360.0f, n, 4, s);
            return s;
        },
        kPi * R * std::sqrt(R * R + h * h));
}

TEST(Quadrics, DiskFacesPlusZ) {
    SurfaceMesh m;
    ASSERT_TRUE(tessellateDisk(0.5f, 2.0f, 180.0f, 64, 3, m));
    test::expectWellFormed(m);
    for (size_t i = 0; i < m.mesh.p.size(); ++i) {
        EXPECT_FLOAT_EQ(m.mesh.p[i].z, 0.5f);
        EXPECT_LE(glm::length(glm::vec2(m.mesh.p[i])), 2.0f + 1e-5f);
        EXPECT_NEAR(m.mesh.n[i].z, 1.0f, 1e-5f);
    }
    expectAreaConverges(
        [](int n) {
            SurfaceMesh s;
            tessellateDisk(0.5f, 2.0f, 180.0f, n, 3, s);
            return s;
        },
        0.5 * kPi * 4.0);
}

TEST(Quadrics, TorusOnSurfaceAreaNormals) {
    float R = 3.0f, r = 1.0f;
    SurfaceMesh m;
    ASSERT_TRUE(tessellateTorus(R, r, -90.0f, 180.0f, 300.0f, 64, 32, m));
    test::expectWellFormed(m);
    for (size_t i = 0; i < m.mesh.p.size(); ++i) {
        glm::vec3 p = m.mesh.p[i];
        float rho = std::hypot(p.x, p.y);
        EXPECT_NEAR((rho - R) * (rho - R) + p.z * p.z, r * r, 1e-4f);
        glm::vec3 ring = glm::vec3(p.x, p.y, 0.0f) * (R / rho);
        EXPECT_GT(glm::dot(m.mesh.n[i], glm::normalize(p - ring)), 0.999f);
    }
    double tm = 300.0 * kPi / 180.0, p0 = -kPi / 2, p1 = kPi;
    double exact = tm * r * (R * (p1 - p0) + r * (std::sin(p1) - std::sin(p0)));
    expectAreaConverges(
        [&](int n) {
            SurfaceMesh s;
            tessellateTorus(R, r, -90.0f, 180.0f, 300.0f, n, n, s);
            return s;
        },
        exact);
}

TEST(Quadrics, ParaboloidOnSurfaceAndArea) {
    float rmax = 1.0f, zmin = 0.0f, zmax = 2.0f;
    SurfaceMesh m;
    ASSERT_TRUE(tessellateParaboloid(rmax, zmin, zmax, 360.0f, 48, 24, m));
    test::expectWellFormed(m);
    for (size_t i = 0; i < m.mesh.p.size(); ++i) {
        glm::vec3 p = m.mesh.p[i];
        EXPECT_NEAR(p.z / zmax, (p.x * p.x + p.y * p.y) / (rmax * rmax), 1e-5f);
        glm::vec3 n = m.mesh.n[i];
        // gradient of z - a rho^2 is (-2a x, -2a y, 1): the spec's normal points away
        // from the axis and down (outward of the bowl).
        glm::vec3 g = glm::normalize(glm::vec3(2.0f * zmax * p.x, 2.0f * zmax * p.y, -1.0f));
        EXPECT_GT(glm::dot(n, g), 0.999f) << i;
    }
    // z = a rho^2; area = pi/(6 a^2) [(1 + 4 a^2 rho^2)^1.5] from 0 to rmax
    double a = zmax / (rmax * rmax);
    double exact = kPi / (6 * a * a) * (std::pow(1 + 4 * a * a * rmax * rmax, 1.5) - 1.0);
    expectAreaConverges(
        [&](int n) {
            SurfaceMesh s;
            tessellateParaboloid(rmax, zmin, zmax, 360.0f, n, n, s);
            return s;
        },
        exact);
    std::string err;
    EXPECT_FALSE(tessellateParaboloid(1.0f, 0.0f, 0.0f, 360.0f, 8, 8, m, &err));
    EXPECT_FALSE(err.empty());
}

TEST(Quadrics, HyperboloidRuledSurface) {
    glm::vec3 p1(1.0f, 0.0f, -1.0f), p2(0.0f, 1.0f, 1.0f);
    SurfaceMesh m;
    ASSERT_TRUE(tessellateHyperboloid(p1, p2, 360.0f, 64, 16, m));
    test::expectWellFormed(m);
    for (size_t i = 0; i < m.mesh.p.size(); ++i) {
        glm::vec3 p = m.mesh.p[i];
        float v = m.st[i].y;
        glm::vec3 q = p1 + v * (p2 - p1);
        EXPECT_NEAR(p.x * p.x + p.y * p.y, q.x * q.x + q.y * q.y, 1e-5f);
        EXPECT_NEAR(p.z, q.z, 1e-5f);
    }
    // A hyperboloid from (R,0,0) to (0,0,h) is a cone: same area as Cone(h, R).
    float R = 1.5f, h = 2.0f;
    expectAreaConverges(
        [&](int n) {
            SurfaceMesh s;
            tessellateHyperboloid(glm::vec3(R, 0, 0), glm::vec3(0, 0, h), 360.0f, n, 2, s);
            return s;
        },
        kPi * R * std::sqrt(R * R + h * h));
    // ... and one with a vertical line is a cylinder, with outward normals.
    SurfaceMesh c;
    ASSERT_TRUE(tessellateHyperboloid(glm::vec3(1, 0, 0), glm::vec3(1, 0, 2), 360.0f, 16, 2, c));
    for (size_t i = 0; i < c.mesh.p.size(); ++i)
        EXPECT_GT(glm::dot(c.mesh.n[i], glm::vec3(c.mesh.p[i].x, c.mesh.p[i].y, 0.0f)), 0.0f);
}

TEST(Quadrics, RejectsNonFiniteAndCapsDensity) {
    SurfaceMesh m;
    std::string err;
    EXPECT_FALSE(tessellateCylinder(NAN, 0, 1, 360, 8, 8, m, &err));
    EXPECT_FALSE(err.empty());
    EXPECT_TRUE(m.mesh.p.empty());
    ASSERT_TRUE(tessellateCylinder(1, 0, 1, 360, 1 << 30, 1, m));
    EXPECT_LE(m.mesh.p.size(), size_t(2 * (kMaxGridSegments + 1)));
    SurfaceMesh z;
    ASSERT_TRUE(tessellateDisk(0, 1, 360, -5, 0, z));  // clamped to 1x1
    EXPECT_EQ(z.mesh.p.size(), 4u);
}
