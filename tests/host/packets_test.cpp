// packets_test.cpp: the packet kernels (cl/lib/packet_traverse.clh, eight rays a
// work-item) against the one-ray kernels, bit for bit: intersect_shadow built with
// RT_SHADOW_PACKETS occludes exactly the rays the one-ray kernel does, intersect_closest
// built with RT_CLOSEST_PACKETS finds the same hits (coherent and incoherent packets, rays
// along shared edges and through coincident triangles, rays leaving a triangle, degenerate
// and dead rays, several lights); and the renderer's image is the same with and without
// packets.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "bvh/collapse4.h"
#include "cl/include/quadric.h"
#include "cl/include/ray.h"
#include "ocl/buffer.h"
#include "ocl/kernel.h"
#include "ocl/program.h"
#include "render/device_scene.h"
#include "render/scene_bvh.h"
#include "render_harness.h"

using namespace rd;

namespace {

// A triangle soup around the origin plus a grid of quads split along shared edges at
// z = 0 (rays through its edges and vertices test the watertight fallback).
std::vector<Triangle> scene(uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> U(-1.0f, 1.0f);
    std::vector<Triangle> t;
    for (int i = 0; i < 2000; ++i) {
        float cx = 5 * U(rng), cy = 5 * U(rng), cz = 2 + 3 * U(rng);
        auto p = [&] { return rt_float4{cx + 0.5f * U(rng), cy + 0.5f * U(rng), cz + 0.5f * U(rng), 0}; };
        t.push_back({p(), p(), p()});
    }
    for (int y = -4; y < 4; ++y)
        for (int x = -4; x < 4; ++x) {
            rt_float4 a{float(x), float(y), 0, 0}, b{float(x + 1), float(y), 0, 0},
                c{float(x + 1), float(y + 1), 0, 0}, d{float(x), float(y + 1), 0, 0};
            t.push_back({a, b, c});
            t.push_back({a, c, d});
        }
    return t;
}

struct ShadowRays {
    std::vector<rt_float4> org, dir;
    std::vector<RayState> state;
};

// `shaded` points with `lights` shadow rays each (slot = point * lights + light).
ShadowRays shadowRays(size_t shaded, uint32_t lights, const std::vector<Triangle>& tris) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> U(-1.0f, 1.0f);
    ShadowRays r;
    const rt_float4 lightPos[3] = {{0.3f, 0.2f, 9.0f, 0}, {-7.0f, 1.0f, 4.0f, 0}, {2.0f, -6.0f, -5.0f, 0}};
    const size_t grid = tris.size() - 128;  // the first grid triangle
    for (size_t s = 0; s < shaded; ++s) {
        // runs of coherent points (neighbouring pixels), then scattered ones
        rt_float4 p;
        uint32_t from = RT_NO_HIT;
        const size_t kind = (s / 24) % 4;
        if (kind == 0) {  // just below the grid, leaving its triangle (fromSurface): only
                          // the skip keeps the rays up from hitting it again
            from = uint32_t(grid + (s * 7) % 128);
            const Triangle& t = tris[from];
            float a = 0.2f + 0.1f * float(s % 5), b = 0.3f;
            p = {t.v0.x + a * (t.v1.x - t.v0.x) + b * (t.v2.x - t.v1.x),
                 t.v0.y + a * (t.v1.y - t.v0.y) + b * (t.v2.y - t.v1.y), -1e-3f, 0.0f};
        } else if (kind == 1) {  // a coherent patch below the grid
            p = {-2.0f + 0.05f * float(s % 24), 1.0f + 0.01f * float(s % 7), -3.0f, 0.0f};
        } else if (kind == 2) {  // on grid vertices and edges, from below
            p = {float(int(s % 8) - 4), float(int(s % 5) - 2) + 0.5f * float(s % 2), -1.0f, 0.0f};
        } else {  // anywhere
            p = {6 * U(rng), 6 * U(rng), 6 * U(rng), 0.0f};
        }
        for (uint32_t l = 0; l < lights; ++l) {
            rt_float4 d{lightPos[l].x - p.x, lightPos[l].y - p.y, lightPos[l].z - p.z, 0};
            float len = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
            if (kind == 2) d = {0.0f, 0.0f, 1.0f, 0.0f}, len = 9.0f;  // straight up an edge
            rt_float4 o = p;
            o.w = 1e-4f;  // tmin
            r.org.push_back(o);
            r.dir.push_back({d.x / len, d.y / len, d.z / len, len * (1.0f - 1e-5f)});
            RayState st{1u, 0u, from, 0.0f};
            const size_t slot = s * lights + l;
            if (slot % 9 == 4 || (s / 8) % 13 == 5) st.alive = 0u;  // dead lanes, a whole dead packet
            r.state.push_back(st);
        }
    }
    // degenerate rays: a zero and a non-finite direction
    r.dir[5] = {0, 0, 0, 1e30f};
    r.dir[6 * lights] = {NAN, 0, 1, 1e30f};
    return r;
}

// A triangle scene's eight- and sixteen-wide trees, the packets' two widths, as the
// renderer's device buffer holds them (128-byte node units) with the option that builds
// the kernels for each.
struct WideTree {
    std::string option;
    std::vector<Bvh4Node> nodes;
    std::vector<Triangle4> blocks;
};
std::vector<WideTree> wideTrees(const std::vector<Triangle>& tris) {
    Scene s;
    s.triangles = tris;
    const Bvh bvh = buildBvh(triangleBounds(s), sceneBvhSettings());
    const Bvh8 b8 = collapseToBvh8(bvh, tris);
    const Bvh16 b16 = collapseToBvh16(bvh, tris);
    return {{"-DRT_BVH8 ", inNodeUnits(b8.nodes), b8.blocks},
            {"-DRT_BVH16 ", inNodeUnits(b16.nodes), b16.blocks}};
}

// The weights after intersect_shadow built with `options`, and its active count.
std::vector<rt_float4> traceShadows(const std::string& options, const WideTree& tree,
                                    const ShadowRays& r, uint32_t lights, bool packets,
                                    uint64_t* active, std::vector<RayState>* after) {
    const ClContext& ctx = test::testContext();
    Program program(ctx, assembleClSource({"intersect.cl"}),
                    "-cl-std=CL1.2 " + tree.option + options);
    Profiler prof(ctx);
    Kernel shadow(ctx, program.get(), "intersect_shadow", prof);
    DeviceBuffer<Bvh4Node> nodes(ctx, tree.nodes);
    DeviceBuffer<Triangle4> blocks(ctx, tree.blocks);
    DeviceBuffer<rt_float4> ob(ctx, r.org), db(ctx, r.dir);
    DeviceBuffer<RayState> state(ctx, r.state);
    const size_t n = r.org.size();
    DeviceBuffer<rt_float4> weight(
        ctx, std::vector<rt_float4>(n, rt_float4{0.5f, 0.25f, 2.0f, 0.0f}), CL_MEM_READ_WRITE);
    DeviceBuffer<Quadric> noQuadrics(ctx, 1);
    DeviceBuffer<uint32_t> noCsg(ctx, 1), noSample(ctx, 1), noNumerics(ctx, 1);
    DeviceBuffer<Triangle> noTris(ctx, 1);
    DeviceBuffer<rt_float4> noMotion(ctx, 1);
    DeviceBuffer<float> noTime(ctx, 1);
    const size_t shaded = n / lights;
    const size_t items = packets ? (shaded + RT_PACKET_RAYS - 1) / RT_PACKET_RAYS * lights : n;
    shadow.launch(items, cl_uint(n), nodes, blocks, ob, db, state, weight, noQuadrics,
                  noCsg, noTris, noMotion, noTris, noSample, noTime, cl_uint(lights),
                  noNumerics, noNumerics, noNumerics, noNumerics,
                  noNumerics, noNumerics);  // (no attrs, materials, AOVs: opaque shadows)
    *active = shadow.peekActive();
    *after = state.download();
    return weight.download();
}

}  // namespace

TEST(Packets, ShadowRaysOccludeExactlyWhatTheOneRayKernelDoes) {
    std::vector<Triangle> tris = scene(5);
    for (const WideTree& b8 : wideTrees(tris)) {
        for (uint32_t lights : {1u, 3u}) {
            const size_t shaded = 1021;  // not a whole number of packets
            ShadowRays r = shadowRays(shaded, lights, tris);
            size_t live = 0;
            for (const RayState& st : r.state) live += st.alive;
            uint64_t activeOne = 0, activePackets = 0;
            std::vector<RayState> afterOne, afterPackets;
            std::vector<rt_float4> one =
                traceShadows("", b8, r, lights, false, &activeOne, &afterOne);
            std::vector<rt_float4> packets = traceShadows("-DRT_SHADOW_PACKETS", b8, r, lights,
                                                          true, &activePackets, &afterPackets);
            ASSERT_EQ(one.size(), packets.size());
            int occluded = 0, differ = 0, stateChanged = 0;
            for (size_t i = 0; i < one.size(); ++i) {
                occluded += one[i].x == 0.0f;
                differ += one[i].x != packets[i].x || one[i].y != packets[i].y ||
                          one[i].z != packets[i].z || one[i].w != packets[i].w;
                stateChanged += afterPackets[i].alive != r.state[i].alive;
                if (!r.state[i].alive) {
                    EXPECT_EQ(packets[i].x, 0.5f) << "dead ray " << i << " touched";
                }
            }
            EXPECT_EQ(differ, 0) << lights << " lights, " << b8.option;
            EXPECT_EQ(stateChanged, 0);
            // both cases occur, and not only on dead rays
            EXPECT_GT(occluded, int(one.size()) / 10) << lights << " lights";
            EXPECT_LT(occluded, int(live) * 9 / 10) << lights << " lights";
            // the occupancy counts rays, one per live slot, in both forms
            EXPECT_EQ(activeOne, live);
            EXPECT_EQ(activePackets, live);
        }
    }
}

// intersect_closest built with RT_CLOSEST_PACKETS (eight consecutive rays a work-item, a
// packet where they are coherent and share their direction signs, one at a time otherwise)
// finds every ray's hit of the one-ray kernel: t, u, v and triangle bit for bit. The rays:
// coherent runs from a camera-like point (packets), runs straight down onto a grid's
// shared edges and vertices (the watertight fallback; a tie between the two triangles of
// an edge goes to the lower index), runs leaving a grid triangle (fromSurface), scattered
// rays (one at a time), and dead lanes.
TEST(Packets, ClosestHitsAreTheOneRayKernels) {
    std::vector<Triangle> tris = scene(7);
    // a second, coincident copy of part of the grid: exact ties in t
    const size_t grid = tris.size() - 128;
    for (size_t i = grid; i < grid + 40; ++i) tris.push_back(tris[i]);
    std::mt19937 rng(13);
    std::uniform_real_distribution<float> U(-1.0f, 1.0f);
    const size_t n = 3001;
    std::vector<rt_float4> org, dir;
    std::vector<RayState> st;
    for (size_t i = 0; i < n; ++i) {
        const size_t kind = (i / 40) % 4;
        rt_float4 o, d;
        uint32_t from = RT_NO_HIT;
        if (kind == 0) {  // a camera's rays over the scene
            o = {0.1f, -0.2f, 12.0f, 0.0f};
            d = {-0.4f + 0.02f * float(i % 40), -0.3f + 0.015f * float((i / 3) % 40), -1.0f, 0.0f};
        } else if (kind == 1) {  // straight down onto edges and vertices of the grid
            o = {float(int(i % 8) - 4) + 0.5f * float((i / 8) % 2), float(int(i % 5) - 2), 3.0f, 0.0f};
            d = {0.0f, 0.0f, -1.0f, 0.0f};
        } else if (kind == 2) {  // leaving a grid triangle upward
            from = uint32_t(grid + (i * 5) % 128);
            const Triangle& t = tris[from];
            o = {(t.v0.x + t.v1.x + t.v2.x) / 3, (t.v0.y + t.v1.y + t.v2.y) / 3, 0.0f, 0.0f};
            d = {0.1f * U(rng), 0.1f * U(rng), 1.0f, 0.0f};
        } else {  // anywhere
            o = {6 * U(rng), 6 * U(rng), 6 * U(rng), 0.0f};
            d = {U(rng), U(rng), U(rng), 0.0f};
        }
        float l = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
        d = {d.x / l, d.y / l, d.z / l, i % 11 == 7 ? 4.0f : 1e30f};  // some with a finite tmax
        org.push_back(o);
        dir.push_back(d);
        st.push_back(RayState{i % 9 == 4 ? 0u : 1u, 0u, from, 0.0f});
    }
    dir[17] = {0, 0, 0, 1e30f};  // a zero direction: no hit, t = tmax
    const ClContext& ctx = test::testContext();
    auto trace = [&](const WideTree& b8, const std::string& options, size_t items,
                     uint64_t* active) {
        Program program(ctx, assembleClSource({"intersect.cl"}),
                        "-cl-std=CL1.2 " + b8.option + options);
        Profiler prof(ctx);
        Kernel closest(ctx, program.get(), "intersect_closest", prof);
        DeviceBuffer<Bvh4Node> nodes(ctx, b8.nodes);
        DeviceBuffer<Triangle4> blocks(ctx, b8.blocks);
        DeviceBuffer<rt_float4> ob(ctx, org), db(ctx, dir);
        DeviceBuffer<RayState> state(ctx, st);
        DeviceBuffer<RayHit> hits(
            ctx, std::vector<RayHit>(n, RayHit{-1.0f, -1.0f, -1.0f, 12345u}), CL_MEM_READ_WRITE);
        DeviceBuffer<Quadric> noQuadrics(ctx, 1);
        DeviceBuffer<uint32_t> noCsg(ctx, 1), noSample(ctx, 1);
        DeviceBuffer<Triangle> noTris(ctx, 1);
        DeviceBuffer<rt_float4> noMotion(ctx, 1);
        DeviceBuffer<float> noTime(ctx, 1);
        closest.launch(items, cl_uint(n), nodes, blocks, ob, db, state, hits, noQuadrics, noCsg,
                       noTris, noMotion, noTris, noSample, noTime, noSample);
        *active = closest.peekActive();
        return hits.download();
    };
    for (const WideTree& tree : wideTrees(tris)) {
        SCOPED_TRACE(tree.option);
        uint64_t activeOne = 0, activePackets = 0;
        std::vector<RayHit> one = trace(tree, "", n, &activeOne);
        std::vector<RayHit> packets = trace(tree, "-DRT_CLOSEST_PACKETS",
                                            (n + RT_PACKET_RAYS - 1) / RT_PACKET_RAYS,
                                            &activePackets);
        int differ = 0, hit = 0, live = 0;
        for (size_t i = 0; i < n; ++i) {
            live += st[i].alive;
            hit += st[i].alive && one[i].prim != RT_NO_HIT;
            const bool same = one[i].t == packets[i].t && one[i].u == packets[i].u &&
                              one[i].v == packets[i].v && one[i].prim == packets[i].prim;
            differ += !same;
            if (!same && differ < 5)
                ADD_FAILURE() << "ray " << i << ": t " << one[i].t << " vs " << packets[i].t << ", prim "
                              << one[i].prim << " vs " << packets[i].prim;
    }
    EXPECT_EQ(differ, 0) << "of " << n << " rays";
    EXPECT_GT(hit, live / 3);
    EXPECT_EQ(packets[4].prim, 12345u) << "a dead ray is left alone";
    EXPECT_EQ(packets[17].prim, RT_NO_HIT);
    EXPECT_EQ(packets[17].t, 1e30f);
    EXPECT_EQ(activeOne, uint64_t(live));
    EXPECT_EQ(activePackets, uint64_t(live));
    }
}

// The renderer traces a triangle scene's shadow rays and its coherent closest-hit rays (eye
// rays, and here mirror rays off a reflective floor) in packets unless told not to, and
// the image is the same either way, pixel for pixel.
TEST(Packets, ImageIsTheSameWithAndWithoutPackets) {
    const std::string rib =
        "Format 40 40 1\nPixelSamples 2 2\nProjection \"perspective\" \"fov\" 40\n"
        "Translate 0 0 6\nWorldBegin\n"
        "LightSource \"pointlight\" 1 \"from\" [2 3 -2] \"intensity\" 12\n"
        "LightSource \"pointlight\" 2 \"from\" [-3 1 -1] \"intensity\" 8\n"
        "LightSource \"distantlight\" 3 \"from\" [0 1 -1] \"to\" [0 0 0] \"intensity\" 0.5\n"
        "Surface \"plastic\"\n"
        "AttributeBegin\nRotate 30 1 1 0\n"
        "PointsPolygons [4 4 4 4 4 4] [0 1 3 2  4 6 7 5  0 4 5 1  2 3 7 6  0 2 6 4  1 5 7 3] "
        "\"P\" [-0.7 -0.7 -0.7 0.7 -0.7 -0.7 -0.7 0.7 -0.7 0.7 0.7 -0.7 -0.7 -0.7 0.7 0.7 -0.7 "
        "0.7 -0.7 0.7 0.7 0.7 0.7 0.7]\nAttributeEnd\n"
        "Surface \"mirror\" \"Kd\" 0.4 \"Kr\" 0.5\n"
        "Polygon \"P\" [-3 -1.5 -2 3 -1.5 -2 3 -1.5 3 -3 -1.5 3]\nWorldEnd\n";
    RenderSettings with, without;
    without.shadowPackets = false;
    without.closestPackets = false;
    test::Rendered a = test::renderRib(rib, with), b = test::renderRib(rib, without);
    EXPECT_TRUE(a.stats.features.shadowPackets || a.stats.features.bvhWidth < 8)
        << "an eight- or sixteen-wide triangle scene with shadows takes packets";
    EXPECT_FALSE(b.stats.features.shadowPackets);
    EXPECT_TRUE(a.stats.features.closestPackets || a.stats.features.bvhWidth < 8);
    EXPECT_FALSE(b.stats.features.closestPackets);
    ASSERT_EQ(a.pixels.size(), b.pixels.size());
    int differ = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i)
        differ += a.pixels[i].r != b.pixels[i].r || a.pixels[i].g != b.pixels[i].g ||
                  a.pixels[i].b != b.pixels[i].b || a.pixels[i].a != b.pixels[i].a;
    EXPECT_EQ(differ, 0);
    EXPECT_GT(a.mean(0, 0, 0, 40, 40), 0.02);
    EXPECT_EQ(a.stats.shadowRays, b.stats.shadowRays) << "the same shadow rays, counted alike";
    EXPECT_EQ(a.stats.eyeRays, b.stats.eyeRays);
    EXPECT_EQ(a.stats.continuationRays, b.stats.continuationRays) << "the mirror's rays";
    EXPECT_GT(a.stats.continuationRays, 0u);
}
