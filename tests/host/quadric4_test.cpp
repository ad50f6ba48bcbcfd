// quadric4_test.cpp: object blocks of plain quadrics intersected four at once
// (cl/lib/quadric4.clh, host/bvh/quadric_blocks.cpp) against the lane loop they stand in
// for: which blocks get a record, and for random rays through overlapping spheres,
// cylinders, cones, paraboloids, hyperboloids and disks, some swept part of the circle
// (near the origin, 1e5 from it, scaled by 1e-4 and 1e4; from outside and inside, with
// clipped ray intervals) the same hit bit for bit, with and without (u, v).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "bvh/quadric_blocks.h"
#include "ocl/buffer.h"
#include "ocl/kernel.h"
#include "ocl/program.h"
#include "render_harness.h"

using namespace rd;

namespace {

// An object block over the scene's quadrics `lanes` (at most four), each boxed by its
// bounds as the BVH's leaves are.
Triangle4 objectBlock(const Scene& s, const std::vector<uint32_t>& lanes) {
    Triangle4 b{};
    float* lo[3] = {&b.v0x.x, &b.v0y.x, &b.v0z.x};
    float* hi[3] = {&b.v1x.x, &b.v1y.x, &b.v1z.x};
    for (size_t k = 0; k < 4; ++k) {
        b.prim[k] = RT_EMPTY_LANE;
        if (k >= lanes.size()) continue;
        const Aabb& box = s.quadricBounds.at(lanes[k]);
        for (int a = 0; a < 3; ++a) lo[a][k] = box.lo[a], hi[a][k] = box.hi[a];
        b.prim[k] = RT_OBJECT_BIT | lanes[k];
    }
    return b;
}

int32_t recordOffset(const Triangle4& b) {
    int32_t off;
    std::memcpy(&off, &b.v2x.x, sizeof off);
    return off;
}

struct Ray {
    rt_float4 o, d;  // w: tmin, tmax
};

// Each ray against blocks[block]: (t, u, v, 1) or zeros, and the primitive, as raw words.
std::vector<uint32_t> probeBlock(const std::vector<Triangle4>& blocks, uint32_t block,
                                 const Scene& s, const std::vector<Ray>& rays, uint32_t wantUv) {
    const ClContext& ctx = test::testContext();
    // never destroyed, as the test context (render_harness.cpp: Oclgrind crashed at exit)
    static Program& program =
        *new Program(ctx, assembleClSource({"quadric_probe.cl"}), "-cl-std=CL1.2");
    Profiler prof(ctx);
    Kernel k(ctx, program.get(), "object_block_probe", prof);
    std::vector<rt_float4> org, dir;
    for (const Ray& r : rays) org.push_back(r.o), dir.push_back(r.d);
    DeviceBuffer<Triangle4> b(ctx, blocks);
    DeviceBuffer<Quadric> q(ctx, s.quadrics);
    DeviceBuffer<rt_float4> o(ctx, org), d(ctx, dir), hit(ctx, rays.size());
    DeviceBuffer<uint32_t> prim(ctx, rays.size());
    k.launch(rays.size(), cl_uint(rays.size()), cl_uint(block), cl_uint(wantUv), b, q, o, d, hit,
             prim);
    std::vector<rt_float4> h = hit.download();
    std::vector<uint32_t> p = prim.download(), out;
    for (size_t i = 0; i < rays.size(); ++i) {
        uint32_t w[4];
        std::memcpy(w, &h[i], sizeof w);
        out.insert(out.end(), {w[0], w[1], w[2], w[3], p[i]});
    }
    return out;
}

}  // namespace

// Blocks of quadrics with a plain one (disks and partial sweeps are plain) get a record,
// their other lanes (a torus, an annulus, a partly swept hyperboloid, a moving sphere)
// marked to be tested on their own; a block without a plain quadric, or with an instance
// or a triangle, keeps the lane loop.
TEST(QuadricBlocks, OnlyPlainBlocksGetARecord) {
    Scene s = test::sceneOfWorld(
        "Sphere 1 -1 1 360\nCylinder 1 -1 1 360\nCone 2 1 360\nParaboloid 1 0 2 360\n"
        "Hyperboloid 1 0 -1 1 1 1 360\nSphere 1 -1 1 180\nTorus 1 0.25 0 360 360\n"
        "Disk 0 1 360\nHyperboloid 1 0 0 2 0 0 360\nSphere 1 -1 1 -360\n"
        "Hyperboloid 1 0 -1 1 1 1 270\n");
    ASSERT_EQ(s.quadrics.size(), 11u);
    s.quadrics[9].flags |= RT_QF_MOVING;
    for (uint32_t i : {0u, 1u, 2u, 3u, 4u, 5u, 7u}) EXPECT_TRUE(isPlainQuadric(s.quadrics[i])) << i;
    for (uint32_t i : {6u, 8u, 9u, 10u}) EXPECT_FALSE(isPlainQuadric(s.quadrics[i])) << i;
    std::vector<Triangle4> blocks = {objectBlock(s, {0, 1, 2, 3}), objectBlock(s, {4, 5, 7}),
                                     objectBlock(s, {6, 0}),       objectBlock(s, {9, 1, 8}),
                                     objectBlock(s, {8}),          objectBlock(s, {10, 6})};
    Triangle4 tri{};
    tri.prim[0] = 0, tri.prim[1] = tri.prim[2] = tri.prim[3] = RT_EMPTY_LANE;
    blocks.push_back(tri);
    Quadric instance{};  // an instance beside a sphere
    instance.kind = RT_Q_INSTANCE;
    s.quadrics.push_back(instance);
    s.quadricBounds.push_back(s.quadricBounds[0]);
    blocks.push_back(objectBlock(s, {0, 11}));
    const size_t leaves = blocks.size();
    ASSERT_EQ(appendQuadricBlocks(blocks, s.quadrics), 4u);
    ASSERT_EQ(blocks.size(), leaves + 8);
    for (size_t i = 4; i < leaves; ++i) EXPECT_EQ(recordOffset(blocks[i]), 0) << i;
    for (size_t i : {0u, 1u, 2u, 3u}) {
        ASSERT_GT(recordOffset(blocks[i]), 0);
        QuadricBlock qb;
        std::memcpy(&qb, &blocks[i + size_t(recordOffset(blocks[i]))], sizeof qb);
        for (int lane = 0; lane < 4; ++lane) {
            const uint32_t prim = blocks[i].prim[lane];
            const float* rec[] = {&qb.center[0].x, &qb.to_object[4].x, &qb.coef[3].x,
                                  &qb.range[2].x, &qb.sweep.x};
            if (prim == RT_EMPTY_LANE) {  // zero: no NaN from an empty lane
                for (const float* f : rec) EXPECT_EQ(f[lane], 0.0f);
                continue;
            }
            const Quadric& q = s.quadrics[prim & RT_OBJECT_MASK];
            if (!isPlainQuadric(q)) {  // on its own: a NaN sweep
                EXPECT_TRUE(std::isnan((&qb.sweep.x)[lane])) << i << " " << lane;
                continue;
            }
            EXPECT_EQ((&qb.sweep.x)[lane], q.range.w);
            EXPECT_EQ((&qb.center[0].x)[lane], q.center.x);
            EXPECT_EQ((&qb.to_object[4].x)[lane], q.to_object[1].y);
            EXPECT_EQ((&qb.to_object[7].x)[lane], q.to_object[2].y);
            EXPECT_EQ((&qb.coef[3].x)[lane], q.coef.w);
            if (q.kind == RT_Q_DISK) {  // no quadratic; its height and radius for z's clip
                for (int a = 0; a < 4; ++a) EXPECT_EQ((&qb.coef[a].x)[lane], 0.0f);
                EXPECT_EQ((&qb.range[0].x)[lane], 0.0f);
                EXPECT_EQ((&qb.range[1].x)[lane], q.shape.x);
                EXPECT_EQ((&qb.range[2].x)[lane], std::fabs(q.shape.y));
                continue;
            }
            EXPECT_EQ((&qb.range[0].x)[lane], q.range.x);
            EXPECT_EQ((&qb.range[2].x)[lane], q.range.z);
        }
    }
}

// Four at once gives the lane loop's hit bit for bit: t, (u, v) and primitive.
TEST(QuadricBlocks, FourAtOnceEqualTheLaneLoop) {
    const char* objects =
        "TransformBegin Sphere 1 -0.6 0.9 360 TransformEnd\n"
        "TransformBegin Translate 0.5 0.2 0 Rotate 50 1 1 0 Cylinder 0.4 -1 1 360 TransformEnd\n"
        "TransformBegin Translate -0.4 0 0.3 Rotate -30 0 1 0 Cone 1.5 0.7 -360 TransformEnd\n"
        "TransformBegin Translate 0 -0.5 -0.5 Scale 1 2 0.5 Paraboloid 0.8 0.1 1.2 360 TransformEnd\n"
        "TransformBegin Translate 0.3 0.6 0.2 Rotate 80 0 0 1 Hyperboloid 0.3 -0.4 -0.6 0.9 0.2 0.7 360 TransformEnd\n"
        "TransformBegin Translate 0.2 0.3 -0.2 Sphere 0.7 -0.7 0.7 360 TransformEnd\n"
        // the same sphere again: ties in t go to the lower lane
        "TransformBegin Translate 0.2 0.3 -0.2 Sphere 0.7 -0.7 0.7 360 TransformEnd\n"
        // a cylinder's cap, a tilted disk of negative radius, a disk through the others
        "TransformBegin Translate 0.5 0.2 0 Rotate 50 1 1 0 Disk 1 0.4 360 TransformEnd\n"
        "TransformBegin Rotate 70 0 1 0 Disk -0.2 -0.9 -360 TransformEnd\n"
        "TransformBegin Rotate 20 1 0 0 Disk 0.1 1.2 360 TransformEnd\n"
        // partial sweeps, both ways
        "TransformBegin Translate 0.1 -0.2 0.1 Rotate 30 0 1 1 Sphere 0.8 -0.5 0.8 250 TransformEnd\n"
        "TransformBegin Rotate -40 1 0 1 Cylinder 0.6 -0.9 0.9 -200 TransformEnd\n"
        "TransformBegin Translate 0 0.3 0 Rotate 60 1 0 0 Disk 0.2 1 100 TransformEnd\n"
        "TransformBegin Translate -0.2 0 -0.3 Rotate 15 0 0 1 Cone 1.2 0.9 -120 TransformEnd\n"
        "TransformBegin Rotate 110 0 1 0 Paraboloid 0.9 0.2 1.1 300 TransformEnd\n"
        // not plain, tested on their own beside plain lanes: a torus, an annulus, a
        // partly swept hyperboloid
        "TransformBegin Rotate 35 1 0 0 Torus 0.7 0.2 0 360 360 TransformEnd\n"
        "TransformBegin Translate 0 -0.1 0 Rotate 80 0 1 0 Hyperboloid 0.2 0 0.1 1 0.3 0.1 360 TransformEnd\n"
        "TransformBegin Rotate 25 0 0 1 Hyperboloid 0.3 -0.4 -0.6 0.9 0.2 0.7 230 TransformEnd\n";
    struct Placement {
        const char* name;
        std::string transform;
        double scale, shift;
    };
    const Placement placements[] = {{"unit", "", 1.0, 0.0},
                                    {"far", "Translate 1e5 0 0", 1.0, 1e5},
                                    {"tiny", "Scale 1e-4 1e-4 1e-4", 1e-4, 0.0},
                                    {"huge", "Scale 1e4 1e4 1e4", 1e4, 0.0}};
    for (const Placement& pl : placements) {
        SCOPED_TRACE(pl.name);
        Scene s = test::sceneOfWorld(pl.transform + "\n" + objects);
        ASSERT_EQ(s.quadrics.size(), 18u);
        std::vector<Triangle4> fast = {objectBlock(s, {0, 1, 2, 3}), objectBlock(s, {4, 5, 6}),
                                       objectBlock(s, {7, 0, 8, 9}),
                                       objectBlock(s, {10, 11, 12, 13}),
                                       objectBlock(s, {14, 2, 10}),
                                       objectBlock(s, {15, 0, 16, 1}),
                                       objectBlock(s, {17, 15, 5, 16})};
        ASSERT_EQ(appendQuadricBlocks(fast, s.quadrics), 7u);
        std::vector<Triangle4> loop = fast;
        for (size_t i = 0; i < 7; ++i) std::memset(&loop[i].v2x.x, 0, sizeof(float));
        std::mt19937 rng(11);
        std::uniform_real_distribution<double> U(-1, 1);
        auto at = [&](double x, double y, double z) {
            return rt_float4{float(pl.shift + x * pl.scale), float(y * pl.scale),
                             float(z * pl.scale), 0.0f};
        };
        std::vector<Ray> rays;
        for (int i = 0; i < 6000; ++i) {
            const bool inside = i % 3 == 0;  // from inside the objects' region
            double ox = 1.3 * U(rng), oy = 1.3 * U(rng), oz = 1.3 * U(rng);
            if (!inside) {
                const double len = std::sqrt(ox * ox + oy * oy + oz * oz) + 1e-9;
                ox *= 6 / len, oy *= 6 / len, oz *= 6 / len;
            }
            const double tx = U(rng), ty = U(rng), tz = U(rng);
            Ray r;
            r.o = at(ox, oy, oz);
            r.d = rt_float4{float(tx - ox), float(ty - oy), float(tz - oz), 0.0f};
            const double t = std::sqrt(double(r.d.x) * r.d.x + double(r.d.y) * r.d.y +
                                       double(r.d.z) * r.d.z);
            r.d.x = float(r.d.x / t), r.d.y = float(r.d.y / t), r.d.z = float(r.d.z / t);
            // a clipped interval for a quarter of the rays (as later hits lower tmax)
            r.o.w = i % 4 == 1 ? float((2 + U(rng)) * pl.scale) : 0.0f;
            r.d.w = i % 4 == 2 ? float((5 + 2 * U(rng)) * pl.scale) : INFINITY;
            rays.push_back(r);
        }
        for (uint32_t block = 0; block < 7; ++block) {
            // (u, v): none, at once, or deferred to the closest hit's point (RT_UV_*)
            std::vector<uint32_t> now;
            for (uint32_t wantUv : {0u, 1u, 2u}) {
                const std::vector<uint32_t> a = probeBlock(fast, block, s, rays, wantUv),
                                            b = probeBlock(loop, block, s, rays, wantUv);
                size_t hits = 0, differ = 0;
                for (size_t i = 0; i < rays.size(); ++i) {
                    hits += b[5 * i + 3] != 0;
                    differ += std::memcmp(&a[5 * i], &b[5 * i], 5 * sizeof(uint32_t)) != 0;
                }
                EXPECT_EQ(differ, 0u) << "block " << block << " uv " << wantUv;
                EXPECT_GT(hits, rays.size() / 4) << "block " << block;  // not a test of misses
                if (wantUv == 1) now = a;
                // a deferred (u, v) is the one given at once, bit for bit, on either path
                if (wantUv == 2) {
                    EXPECT_EQ(a, now) << "block " << block << ": deferred (u, v), four at once";
                    EXPECT_EQ(b, now) << "block " << block << ": deferred (u, v), lane loop";
                }
            }
        }
    }
}
