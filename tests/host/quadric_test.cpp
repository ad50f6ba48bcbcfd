// quadric_test.cpp: the device's exact quadric and CSG intersection (cl/lib/quadric.clh,
// cl/lib/objects.clh) run through quadric_probe.cl on rays with known answers: distances
// against long-double references, grazing rays down to 1e-7 rad, the stiff torus
// (quartic double roots near tangency), objects far from the origin, (u, v) that map back
// to the hit point, and CSG boundaries whose normals face the ray. Each case prints its
// measured error as "NUMERICS case=... tolerance=... measured=...".
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "ocl/buffer.h"
#include "ocl/kernel.h"
#include "ocl/program.h"
#include "render_harness.h"
#include "rib/reader.h"
#include "scene/rib_builder.h"

using namespace rd;

namespace {

struct Ray {
    glm::vec3 o, d;
    float tmin = 0.0f, tmax = INFINITY;
};

struct ProbeResult {
    bool hit;
    float t, u, v;
    uint32_t prim;
    glm::vec3 p, n;
    int crossings;
    float cross[3];
};

// Intersects every ray with scene object `object` on the default device.
std::vector<ProbeResult> probe(const Scene& s, uint32_t object, const std::vector<Ray>& rays) {
    const ClContext& ctx = test::testContext();
    // never destroyed, as the test context (render_harness.cpp: Oclgrind crashed at exit)
    static Program& program =
        *new Program(ctx, assembleClSource({"quadric_probe.cl"}), "-cl-std=CL1.2");
    Profiler prof(ctx);
    Kernel k(ctx, program.get(), "quadric_probe", prof);
    std::vector<rt_float4> org, dir;
    for (const Ray& r : rays) {
        org.push_back({r.o.x, r.o.y, r.o.z, r.tmin});
        dir.push_back({r.d.x, r.d.y, r.d.z, r.tmax});
    }
    std::vector<uint32_t> csg = s.csg;
    if (csg.empty()) csg.push_back(0);
    std::vector<Triangle> tris = s.triangles;
    if (tris.empty()) tris.push_back(Triangle{});
    DeviceBuffer<Quadric> q(ctx, s.quadrics);
    DeviceBuffer<uint32_t> c(ctx, csg);
    DeviceBuffer<Triangle> t(ctx, tris);
    DeviceBuffer<rt_float4> o(ctx, org), d(ctx, dir), hit(ctx, rays.size()), pos(ctx, rays.size()),
        nrm(ctx, rays.size()), cross(ctx, rays.size());
    DeviceBuffer<uint32_t> prim(ctx, rays.size());
    k.launch(rays.size(), cl_uint(rays.size()), cl_uint(object), q, c, t, o, d, hit, prim, pos,
             nrm, cross);
    std::vector<rt_float4> h = hit.download(), p = pos.download(), n = nrm.download(),
                           x = cross.download();
    std::vector<uint32_t> pr = prim.download();
    std::vector<ProbeResult> out(rays.size());
    for (size_t i = 0; i < rays.size(); ++i)
        out[i] = {h[i].w != 0.0f, h[i].x, h[i].y, h[i].z, pr[i], {p[i].x, p[i].y, p[i].z},
                  {n[i].x, n[i].y, n[i].z}, int(x[i].w), {x[i].x, x[i].y, x[i].z}};
    return out;
}

void report(const char* name, double tol, double measured) {
    std::printf("NUMERICS case=%s tolerance=%g measured=%g\n", name, tol, measured);
    EXPECT_LE(measured, tol) << name;
}

}  // namespace

// Distances to a moved and scaled sphere against the long-double root of |o + t d - c| = r.
TEST(Quadric, SphereDistancesMatchTheAnalyticRoot) {
    Scene s = test::sceneOfWorld("Translate 3 -2 5 Scale 2 2 2 Sphere 1 -1 1 360");
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> U(-1, 1);
    const glm::vec3 c(3, -2, 5);
    std::vector<Ray> rays;
    for (int i = 0; i < 256; ++i) {
        glm::vec3 from = c + 20.0f * glm::normalize(glm::vec3(U(rng), U(rng), U(rng)));
        glm::vec3 to = c + 1.9f * glm::vec3(U(rng), U(rng), U(rng)) / 1.8f;
        rays.push_back({from, glm::normalize(to - from)});
    }
    auto res = probe(s, 0, rays);
    double worstT = 0, worstP = 0, worstN = 0;
    int misses = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        const Ray& r = rays[i];
        long double ox = r.o.x - c.x, oy = r.o.y - c.y, oz = r.o.z - c.z;
        long double b = ox * r.d.x + oy * r.d.y + oz * r.d.z;
        long double dd = (long double)r.d.x * r.d.x + (long double)r.d.y * r.d.y +
                         (long double)r.d.z * r.d.z;
        long double cc = ox * ox + oy * oy + oz * oz - 4.0L;
        long double disc = b * b - dd * cc;
        if (disc < 0) continue;
        long double t = (-b - std::sqrt(disc)) / dd;
        if (!res[i].hit) {
            ++misses;
            continue;
        }
        worstT = std::max(worstT, double(std::fabs(res[i].t - t) / t));
        worstP = std::max(worstP, double(std::fabs(glm::length(res[i].p - c) - 2.0f) / 2.0f));
        glm::vec3 nExp = glm::normalize(res[i].p - c);
        worstN = std::max(worstN, double(glm::length(res[i].n - nExp)));
    }
    EXPECT_EQ(misses, 0);
    report("sphere_distance_rel", 1e-6, worstT);
    report("sphere_point_on_surface_rel", 1e-6, worstP);
    report("sphere_normal", 1e-5, worstN);
}

// Rays grazing the top of a sphere at depth delta below its tangent plane: the crossing
// angle is about sqrt(2 delta / r), down to 1.4e-7 rad; every one must hit (two
// crossings), every ray above the plane must miss.
TEST(Quadric, GrazingRaysOnASphereNeverMiss) {
    Scene s = test::sceneOfWorld("Translate 0 -1 0 Sphere 1 -1 1 360");
    std::vector<Ray> rays;
    std::vector<double> deltas;
    for (int k = 2; k <= 14; ++k) {
        double delta = std::pow(10.0, -k);
        deltas.push_back(delta);
        // start just outside the chord, so t is small and its float spacing fine
        rays.push_back({{float(-(std::sqrt(2 * delta) + 1e-3)), float(-delta), 0.0f}, {1, 0, 0}});
    }
    for (int k = 2; k <= 14; ++k)
        rays.push_back({{-1e-3f, float(std::pow(10.0, -k)), 0.0f}, {1, 0, 0}});
    auto res = probe(s, 0, rays);
    double worst = 0;
    for (size_t i = 0; i < deltas.size(); ++i) {
        SCOPED_TRACE("delta " + std::to_string(deltas[i]));
        EXPECT_TRUE(res[i].hit);
        EXPECT_EQ(res[i].crossings, 2);
        long double y = (long double)rays[i].o.y;  // the float the ray really has
        long double half = std::sqrt(-2.0L * y - y * y);
        long double t = -(long double)rays[i].o.x - half;
        worst = std::max(worst, double(std::fabs(res[i].t - t)));
    }
    for (size_t i = deltas.size(); i < rays.size(); ++i) EXPECT_FALSE(res[i].hit);
    report("sphere_grazing_abs_t", 2e-9, worst);
}

// The stiff torus: rays just under the top of the tube cross it at two nearly double
// roots on each side (x = +-R +- sqrt(2 r delta - delta^2)); the depressed quartic must
// give all four, near and far from the origin, against long double.
TEST(Quadric, TorusNearTangencyGivesAllFourRoots) {
    Scene s = test::sceneOfWorld("Translate 0 0 -0.25 Torus 1 0.25 0 360 360");
    struct Case {
        double delta, x0;
    };
    std::vector<Case> cases;
    std::vector<Ray> rays;
    for (double x0 : {-3.0, -1000.0})
        for (int k = 2; k <= 12; ++k) {
            double delta = std::pow(10.0, -k);
            cases.push_back({delta, x0});
            rays.push_back({{float(x0), 0.0f, float(-delta)}, {1, 0, 0}});
        }
    auto res = probe(s, 0, rays);
    double worstNear = 0, worstFar = 0;
    for (size_t i = 0; i < cases.size(); ++i) {
        SCOPED_TRACE("delta " + std::to_string(cases[i].delta) + " x0 " +
                     std::to_string(cases[i].x0));
        long double z = (long double)rays[i].o.z + 0.25L;  // height in the torus's space
        long double h = std::sqrt(0.0625L - z * z);
        long double x0 = rays[i].o.x;
        long double expect[4] = {-1 - h - x0, -1 + h - x0, 1 - h - x0, 1 + h - x0};
        EXPECT_EQ(res[i].crossings, 4);
        ASSERT_TRUE(res[i].hit);
        double err = std::max({std::fabs(res[i].cross[0] - expect[0]),
                               std::fabs(res[i].cross[1] - expect[1]),
                               std::fabs(res[i].cross[2] - expect[2])}) /
                     double(std::fabs(x0) + 2);
        (cases[i].x0 < -10 ? worstFar : worstNear) =
            std::max(cases[i].x0 < -10 ? worstFar : worstNear, err);
    }
    report("torus_tangent_rel_t_near", 2e-7, worstNear);
    report("torus_tangent_rel_t_far", 2e-7, worstFar);
    // just above the tube: no crossing at all
    auto miss = probe(s, 0, {{{-3, 0, 1e-7f}, {1, 0, 0}}, {{-3, 0, 1e-3f}, {1, 0, 0}}});
    EXPECT_FALSE(miss[0].hit);
    EXPECT_FALSE(miss[1].hit);
}

// Every kind, clipped and swept: the point the hit's (u, v) evaluates to is where the ray
// met the surface, and closed surfaces are crossed an even number of times.
TEST(Quadric, EveryKindMapsItsHitsBackThroughUV) {
    const char* shapes[] = {
        "Sphere 1 -0.5 0.8 300",        "Cylinder 0.7 -0.5 0.9 270",
        "Cone 1.2 0.8 330",             "Disk 0.3 0.9 200",
        "Paraboloid 0.9 0.1 1.1 310",   "Hyperboloid 0.8 -0.2 -0.6 -0.3 0.7 0.6 290",
        "Torus 0.8 0.3 -60 200 280",    "Hyperboloid 0.2 0 0.3 0.9 0.4 0.3 360",
        "Sphere 1 -1 1 360",            "Torus 0.8 0.3 0 360 360"};
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> U(-1, 1);
    for (const char* shape : shapes) {
        SCOPED_TRACE(shape);
        Scene s = test::sceneOfWorld(std::string("Translate 0.3 -0.2 0.1 Rotate 35 1 1 0 Scale 1 1.5 0.8 ") + shape);
        ASSERT_EQ(s.quadrics.size(), 1u);
        std::vector<Ray> rays;
        for (int i = 0; i < 400; ++i) {
            glm::vec3 from = 6.0f * glm::normalize(glm::vec3(U(rng), U(rng), U(rng)));
            glm::vec3 to(U(rng), U(rng), U(rng));
            rays.push_back({from, glm::normalize(to - from)});
        }
        auto res = probe(s, 0, rays);
        int hits = 0, odd = 0;
        double worst = 0;
        for (size_t i = 0; i < rays.size(); ++i) {
            if (!res[i].hit) continue;
            ++hits;
            glm::vec3 at = rays[i].o + res[i].t * rays[i].d;
            worst = std::max(worst, double(glm::length(at - res[i].p)));
            odd += res[i].crossings % 2;
        }
        EXPECT_GT(hits, 20);
        EXPECT_LE(worst, 2e-5) << "hit point and P(u, v) disagree";
        if (std::string(shape) == "Sphere 1 -1 1 360" || std::string(shape).rfind("Torus 0.8 0.3 0 360", 0) == 0) {
            EXPECT_EQ(odd, 0) << "a closed surface crossed an odd number of times";
        }
    }
}

// A sphere of radius 100 at 1e5 from the origin, seen from the origin: distances stay
// exact to float precision and P(u, v) lies on the surface to the float spacing there.
TEST(Quadric, FarFromTheOriginKeepsItsPrecision) {
    Scene s = test::sceneOfWorld("Translate 100000 0 0 Sphere 100 -100 100 360");
    std::vector<Ray> rays;
    for (int i = 0; i < 64; ++i) {
        float y = -90.0f + 180.0f * float(i) / 63.0f;
        rays.push_back({{0, 0, 0}, glm::normalize(glm::vec3(1e5f, y, 0.3f * y))});
    }
    auto res = probe(s, 0, rays);
    double worstT = 0, worstP = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        ASSERT_TRUE(res[i].hit);
        long double dx = rays[i].d.x, dy = rays[i].d.y, dz = rays[i].d.z;
        long double b = -1e5L * dx, cc = 1e10L - 1e4L;
        long double dd = dx * dx + dy * dy + dz * dz;
        long double t = (-b - std::sqrt(b * b - dd * cc)) / dd;
        worstT = std::max(worstT, double(std::fabs(res[i].t - t) / t));
        worstP = std::max(worstP, double(std::fabs(glm::length(res[i].p - glm::vec3(1e5f, 0, 0)) - 100.0f)));
    }
    report("far_sphere_rel_t", 2e-7, worstT);
    report("far_sphere_point_abs", 0.02, worstP);  // float spacing at 1e5 is 0.0078
}

// CSG: whatever the ray, the visible boundary's normal faces it (for a subtracted
// surface that is the reversed normal), and no hit lies inside a subtracted part.
TEST(Quadric, CsgBoundariesFaceTheRay) {
    Scene s = test::sceneOfWorld(R"(SolidBegin "difference"
        SolidBegin "primitive" Sphere 1 -1 1 360 SolidEnd
        SolidBegin "primitive" Cylinder 0.5 -2 2 360 Disk -2 0.5 360 Disk 2 0.5 360 SolidEnd
        SolidBegin "intersection"
          SolidBegin "primitive" AttributeBegin Translate 0 0 1 Sphere 0.6 -0.6 0.6 360
            AttributeEnd SolidEnd
          SolidBegin "primitive" AttributeBegin Translate 0.3 0 1 Sphere 0.6 -0.6 0.6 360
            AttributeEnd SolidEnd
        SolidEnd
      SolidEnd)");
    ASSERT_FALSE(s.quadrics.empty());
    ASSERT_EQ(s.quadrics.back().kind, RT_Q_CSG);
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> U(-1, 1);
    std::vector<Ray> rays;
    for (int i = 0; i < 2000; ++i) {
        glm::vec3 from = 5.0f * glm::normalize(glm::vec3(U(rng), U(rng), U(rng)));
        glm::vec3 to = 0.9f * glm::vec3(U(rng), U(rng), U(rng));
        rays.push_back({from, glm::normalize(to - from)});
    }
    auto res = probe(s, uint32_t(s.quadrics.size() - 1), rays);
    int hits = 0, facing = 0, inside = 0, holeWalls = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        if (!res[i].hit) continue;
        ++hits;
        facing += glm::dot(res[i].n, rays[i].d) < 0.0f;
        glm::vec3 p = res[i].p;
        float rho = std::sqrt(p.x * p.x + p.y * p.y);
        inside += rho < 0.5f - 1e-4f;  // inside the drilled hole
        holeWalls += std::fabs(rho - 0.5f) < 1e-4f;
    }
    EXPECT_GT(hits, 500);
    EXPECT_GT(holeWalls, 10);
    EXPECT_EQ(inside, 0);
    report("csg_normals_not_facing_fraction", 0.0, double(hits - facing) / hits);
}
