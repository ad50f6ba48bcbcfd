// wide_bvh_test.cpp: the four- and eight-wide collapses of the binary SAH tree
// (host/bvh/collapse4.h) keep every triangle exactly once, and the eight-wide traversal
// (cl/lib/traverse.clh with RT_BVH8, the renderer's choice on a CPU device)
// finds the same closest hits as a brute-force search in double precision.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <type_traits>

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
using rd::test::Rendered;
using rd::test::renderRib;

namespace {

std::vector<Triangle> soup(size_t n, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> U(-1.0f, 1.0f);
    std::vector<Triangle> t;
    for (size_t i = 0; i < n; ++i) {
        float cx = 5 * U(rng), cy = 5 * U(rng), cz = 5 * U(rng);
        auto p = [&] { return rt_float4{cx + 0.4f * U(rng), cy + 0.4f * U(rng), cz + 0.4f * U(rng), 0}; };
        t.push_back({p(), p(), p()});
    }
    return t;
}

template <class Wide>
std::vector<int> primCounts(const Wide& w, size_t tris) {
    std::vector<int> seen(tris, 0);
    for (const Triangle4& b : w.blocks)
        for (uint32_t p : b.prim)
            if (p != RT_EMPTY_LANE) ++seen.at(p);
    return seen;
}

// Closest hit by a plain double-precision Moller-Trumbore over every triangle.
double bruteForce(const std::vector<Triangle>& tris, const rt_float4& o, const rt_float4& d,
                  uint32_t& prim) {
    double best = 1e30;
    prim = RT_NO_HIT;
    for (size_t i = 0; i < tris.size(); ++i) {
        const Triangle& t = tris[i];
        double e1[3] = {t.v1.x - t.v0.x, t.v1.y - t.v0.y, t.v1.z - t.v0.z};
        double e2[3] = {t.v2.x - t.v0.x, t.v2.y - t.v0.y, t.v2.z - t.v0.z};
        double dv[3] = {d.x, d.y, d.z};
        double p[3] = {dv[1] * e2[2] - dv[2] * e2[1], dv[2] * e2[0] - dv[0] * e2[2],
                       dv[0] * e2[1] - dv[1] * e2[0]};
        double det = e1[0] * p[0] + e1[1] * p[1] + e1[2] * p[2];
        if (std::fabs(det) < 1e-12) continue;
        double s[3] = {o.x - t.v0.x, o.y - t.v0.y, o.z - t.v0.z};
        double u = (s[0] * p[0] + s[1] * p[1] + s[2] * p[2]) / det;
        double q[3] = {s[1] * e1[2] - s[2] * e1[1], s[2] * e1[0] - s[0] * e1[2],
                       s[0] * e1[1] - s[1] * e1[0]};
        double v = (dv[0] * q[0] + dv[1] * q[1] + dv[2] * q[2]) / det;
        double tt = (e2[0] * q[0] + e2[1] * q[1] + e2[2] * q[2]) / det;
        if (u < 0 || v < 0 || u + v > 1 || tt <= 0 || tt >= best) continue;
        best = tt;
        prim = uint32_t(i);
    }
    return best;
}

}  // namespace

// Both collapses keep every triangle exactly once and fill the wide nodes: the greedy
// collapse (open the largest child until there are W) used 58% of a 75k-triangle sphere
// field's eight-wide slots and half of a 1M field's nodes had two children; the SAH
// collapse uses 86-89% (bench_trace). On soups, and on a field of small clusters whose
// binary tree ends in pairs of leaves.
TEST(WideBvh, CollapsesKeepEveryTriangleOnceAndFillTheNodes) {
    std::vector<Triangle> clusters;
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> U(0.0f, 1.0f);
    for (int c = 0; c < 2000; ++c) {  // 2000 clusters of 6 triangles, far apart
        const float cx = 100.0f * U(rng), cy = 100.0f * U(rng), cz = 100.0f * U(rng);
        for (int t = 0; t < 6; ++t) {
            auto p = [&] { return rt_float4{cx + U(rng), cy + U(rng), cz + U(rng), 0}; };
            clusters.push_back({p(), p(), p()});
        }
    }
    for (const std::vector<Triangle>& tris : {soup(5000, 1), soup(20000, 4), clusters}) {
        Scene s;
        s.triangles = tris;
        Bvh bvh = buildBvh(triangleBounds(s), sceneBvhSettings());
        Bvh4 b4 = collapseToBvh4(bvh, tris);
        Bvh8 b8 = collapseToBvh8(bvh, tris);
        Bvh16 b16 = collapseToBvh16(bvh, tris);
        for (int c : primCounts(b4, tris.size())) ASSERT_EQ(c, 1);
        for (int c : primCounts(b8, tris.size())) ASSERT_EQ(c, 1);
        for (int c : primCounts(b16, tris.size())) ASSERT_EQ(c, 1);
        EXPECT_GT(usedSlots(b4), 0.85) << b4.nodes.size() << " nodes";
        EXPECT_GT(usedSlots(b8), 0.7) << b8.nodes.size() << " nodes";
        // (sixteen-wide: 0.83-0.85 on the soups, 0.45 on the clusters, which the SAH lays
        // out in nodes of a few clusters each)
        EXPECT_GT(usedSlots(b16), 0.4) << b16.nodes.size() << " nodes";
        EXPECT_LT(b8.nodes.size(), b4.nodes.size()) << "eight-wide: fewer nodes";
        EXPECT_LT(b16.nodes.size(), b8.nodes.size()) << "sixteen-wide: fewer nodes";
        std::printf(
            "%zu triangles: %zu blocks, four-wide %zu nodes (%.2f), eight-wide %zu "
            "(%.2f), sixteen-wide %zu (%.2f)\n",
            tris.size(), b8.blocks.size(), b4.nodes.size(), usedSlots(b4),
            b8.nodes.size(), usedSlots(b8), b16.nodes.size(), usedSlots(b16));
    }
}

// Whether the subtrees under a's node i and b's node j are the same: the same boxes,
// child kinds and counts slot by slot, the same blocks under each leaf, the same
// subtrees under each interior child (wherever each tree keeps them).
template <class Node>
bool sameSubtree(const BvhWide<Node>& a, int i, const BvhWide<Node>& b, int j) {
    constexpr int W = int(sizeof(Node::count) / sizeof(Node::count[0]));
    const Node &x = a.nodes[size_t(i)], &y = b.nodes[size_t(j)];
    if (std::memcmp(x.planes, y.planes, sizeof x.planes) != 0 ||
        std::memcmp(x.count, y.count, sizeof x.count) != 0)
        return false;
    for (int k = 0; k < W; ++k) {
        if (x.count[k] > 0) {
            if (std::memcmp(&a.blocks[size_t(x.child[k])], &b.blocks[size_t(y.child[k])],
                            sizeof(Triangle4) * size_t(x.count[k])) != 0)
                return false;
        } else if (x.count[k] == 0 && !sameSubtree(a, x.child[k], b, y.child[k])) {
            return false;
        }
    }
    return true;
}

// A tree of kParallelCollapse primitives or more is laid out on the host's cores, its
// subtrees in nodes and blocks of their own appended after the top levels: the nodes and
// blocks in another order than the depth-first walk, the same tree.
TEST(WideBvh, ParallelLayOutIsTheDepthFirstTree) {
    const std::vector<Triangle> tris = soup(150000, 9);
    Scene s;
    s.triangles = tris;
    const Bvh bvh = buildBvh(triangleBounds(s), sceneBvhSettings());
    ASSERT_GE(tris.size(), kParallelCollapse);
    const Bvh8 parallel = collapseToBvh8(bvh, tris);
    const Bvh8 depthFirst = collapseToBvh8(bvh, tris, nullptr, tris.size() + 1);
    ASSERT_EQ(parallel.nodes.size(), depthFirst.nodes.size());
    ASSERT_EQ(parallel.blocks.size(), depthFirst.blocks.size());
    EXPECT_TRUE(sameSubtree(parallel, 0, depthFirst, 0));
    EXPECT_NE(0, std::memcmp(parallel.nodes.data(), depthFirst.nodes.data(),
                             sizeof(Bvh8Node) * parallel.nodes.size()))
        << "the same layout: this test no longer tests the parallel one";
    const Bvh16 parallel16 = collapseToBvh16(bvh, tris);
    const Bvh16 depthFirst16 = collapseToBvh16(bvh, tris, nullptr, tris.size() + 1);
    ASSERT_EQ(parallel16.nodes.size(), depthFirst16.nodes.size());
    EXPECT_TRUE(sameSubtree(parallel16, 0, depthFirst16, 0));
}

// Random rays through the eight- or sixteen-wide tree of a triangle soup, traced by the
// intersect_closest and intersect_shadow kernels, against a brute-force double closest
// hit: the same t within 1e-4 relative; shadow rays cut at half their closest hit are not
// occluded, unbounded ones are exactly when they hit. Every fifth ray is dead and must be
// left alone. `depth`: the rays' trace depth (0: eye rays, which walk the nodes' lanes;
// 1: traced rays, which walk the hit masks).
template <class Node>
static void expectWideHitsMatchBruteForce(uint32_t depth) {
    const ClContext& ctx = test::testContext();
    std::vector<Triangle> tris = soup(3000, 2);
    Scene s;
    s.triangles = tris;
    Bvh bvh = buildBvh(triangleBounds(s), sceneBvhSettings());
    constexpr bool sixteen = std::is_same_v<Node, Bvh16Node>;
    BvhWide<Node> b8;
    if constexpr (sixteen) b8 = collapseToBvh16(bvh, tris);
    else b8 = collapseToBvh8(bvh, tris);
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> U(-1.0f, 1.0f);
    const size_t n = 2045;
    std::vector<rt_float4> org, dir;
    std::vector<RayState> alive(n, RayState{1u, depth, RT_NO_HIT, 0.0f});
    for (size_t i = 0; i < n; ++i) {
        float dx = U(rng), dy = U(rng), dz = U(rng), l = std::sqrt(dx * dx + dy * dy + dz * dz);
        org.push_back({6 * U(rng), 6 * U(rng), 6 * U(rng), 0.0f});
        dir.push_back({dx / l, dy / l, dz / l, 1e30f});
        if (i % 5 == 3) alive[i].alive = 0u;
    }
    // as built for a scene whose shaders trace in sampled directions: traced rays walk the
    // hit masks
    Program program(ctx, assembleClSource({"intersect.cl"}),
                    std::string("-cl-std=CL1.2 -DRT_INCOHERENT_TRACE ") +
                        (sixteen ? "-DRT_BVH16" : "-DRT_BVH8"));
    Profiler prof(ctx);
    Kernel closest(ctx, program.get(), "intersect_closest", prof);
    Kernel shadow(ctx, program.get(), "intersect_shadow", prof);
    DeviceBuffer<Node> nodes(ctx, b8.nodes);
    DeviceBuffer<Triangle4> blocks(ctx, b8.blocks);
    DeviceBuffer<rt_float4> ob(ctx, org), db(ctx, dir);
    DeviceBuffer<RayState> state(ctx, alive);
    const RayHit untouched{-1.0f, -1.0f, -1.0f, 12345u};
    DeviceBuffer<RayHit> hits(ctx, std::vector<RayHit>(n, untouched), CL_MEM_READ_WRITE);
    // the object, motion and sample buffers a triangle-only build does not read
    DeviceBuffer<Quadric> noQuadrics(ctx, 1);
    DeviceBuffer<uint32_t> noCsg(ctx, 1), noSample(ctx, 1), noNumerics(ctx, 1);
    DeviceBuffer<Triangle> noTris(ctx, 1);
    DeviceBuffer<rt_float4> noMotion(ctx, 1);
    DeviceBuffer<float> noTime(ctx, 1);
    closest.launch(n, cl_uint(n), nodes, blocks, ob, db, state, hits, noQuadrics, noCsg, noTris,
                   noMotion, noTris, noSample, noTime, noSample);
    std::vector<RayHit> h = hits.download();
    std::vector<double> best(n);
    std::vector<uint32_t> bestPrim(n);
    int hitsFound = 0, wrong = 0, touchedDead = 0;
    for (size_t i = 0; i < n; ++i) {
        best[i] = bruteForce(tris, org[i], dir[i], bestPrim[i]);
        if (!alive[i].alive) {
            touchedDead += h[i].prim != untouched.prim;
            continue;
        }
        hitsFound += bestPrim[i] != RT_NO_HIT;
        if (bestPrim[i] == RT_NO_HIT ? h[i].prim != RT_NO_HIT
                                     : std::fabs(h[i].t - best[i]) > 1e-4 * std::max(1.0, best[i]))
            ++wrong;
    }
    EXPECT_GT(hitsFound, int(n) / 5);
    EXPECT_EQ(wrong, 0) << "of " << n << " rays";
    EXPECT_EQ(touchedDead, 0);
    // shadow rays: those that hit are cut at half their hit (reach the light) or left
    // unbounded (occluded: their weight zeroed); dead ones are not touched
    std::vector<rt_float4> sdir = dir;
    for (size_t i = 0; i < n; ++i)
        if (bestPrim[i] != RT_NO_HIT && i % 2) sdir[i].w = float(best[i] * 0.5);
    DeviceBuffer<rt_float4> sdb(ctx, sdir);
    state.upload(alive);
    const std::vector<rt_float4> weights(n, rt_float4{0.5f, 0.25f, 2.0f, 0.0f});
    DeviceBuffer<rt_float4> weight(ctx, weights, CL_MEM_READ_WRITE);  // zeroed where occluded
    shadow.launch(n, cl_uint(n), nodes, blocks, ob, sdb, state, weight, noQuadrics, noCsg,
                  noTris, noMotion, noTris, noSample, noTime, cl_uint(1), noNumerics,
                  noNumerics, noNumerics, noNumerics,
                  noNumerics, noNumerics);  // (no attrs, materials, AOVs: opaque shadows)
    std::vector<RayState> after = state.download();
    std::vector<rt_float4> wAfter = weight.download();
    int wrongShadow = 0, stateChanged = 0;
    for (size_t i = 0; i < n; ++i) {
        const bool blocked = alive[i].alive && bestPrim[i] != RT_NO_HIT && !(i % 2);
        const rt_float4 w = wAfter[i];
        const bool zero = w.x == 0 && w.y == 0 && w.z == 0 && w.w == 0;
        const bool kept = w.x == 0.5f && w.y == 0.25f && w.z == 2.0f && w.w == 0;
        wrongShadow += blocked ? !zero : !kept;
        stateChanged += after[i].alive != alive[i].alive;
    }
    EXPECT_EQ(wrongShadow, 0) << "of " << n << " shadow rays";
    EXPECT_EQ(stateChanged, 0) << "the group count reads the states: the kernel keeps them";
}

TEST(WideBvh, EightWideTraversalFindsTheClosestHits) {
    expectWideHitsMatchBruteForce<Bvh8Node>(0);  // the lane walk
    expectWideHitsMatchBruteForce<Bvh8Node>(1);  // the mask walk
}

TEST(WideBvh, SixteenWideTraversalFindsTheClosestHits) {
    expectWideHitsMatchBruteForce<Bvh16Node>(0);
    expectWideHitsMatchBruteForce<Bvh16Node>(1);
}

// The renderer's three node widths give the same image: triangles, exact quadrics and
// instances of an object (whose prototype trees are appended to the node array), with
// shadows; every pixel equal.
TEST(WideBvh, ImageIsTheSameAtEveryNodeWidth) {
    const std::string rib =
        "Format 48 48 1\nPixelSamples 2 2\nProjection \"perspective\" \"fov\" 40\n"
        "Translate 0 0 6\nWorldBegin\n"
        "LightSource \"shadowdistant\" 1 \"from\" [1 2 -1] \"to\" [0 0 0]\n"
        "Surface \"matte\"\nObjectBegin \"box\"\n"
        "PointsPolygons [4 4 4 4 4 4] [0 1 3 2  4 6 7 5  0 4 5 1  2 3 7 6  0 2 6 4  1 5 7 3] "
        "\"P\" [-0.5 -0.5 -0.5 0.5 -0.5 -0.5 -0.5 0.5 -0.5 0.5 0.5 -0.5 -0.5 -0.5 0.5 0.5 -0.5 "
        "0.5 -0.5 0.5 0.5 0.5 0.5 0.5]\nObjectEnd\n"
        "AttributeBegin\nTranslate -1.2 0.3 0 Rotate 30 1 1 0\nObjectInstance \"box\"\nAttributeEnd\n"
        "AttributeBegin\nTranslate 1.2 -0.4 0 Rotate 70 0 1 1\nObjectInstance \"box\"\nAttributeEnd\n"
        "AttributeBegin\nTranslate 0 0.9 0.5\nSphere 0.6 -0.6 0.6 360\nAttributeEnd\n"
        "Polygon \"P\" [-3 -1.5 -2 3 -1.5 -2 3 -1.5 3 -3 -1.5 3]\nWorldEnd\n";
    RenderSettings four, eight, sixteen;
    four.bvhWidth = 4;
    eight.bvhWidth = 8;
    sixteen.bvhWidth = 16;
    Rendered a = renderRib(rib, four), b = renderRib(rib, eight), c = renderRib(rib, sixteen);
    EXPECT_EQ(a.stats.features.bvhWidth, 4);
    EXPECT_EQ(b.stats.features.bvhWidth, 8);
    EXPECT_EQ(c.stats.features.bvhWidth, 16);
    EXPECT_EQ(b.stats.instances, 2u);
    for (const Rendered* r : {&b, &c}) {
        ASSERT_EQ(a.pixels.size(), r->pixels.size());
        int differ = 0;
        for (size_t i = 0; i < a.pixels.size(); ++i)
            differ += a.pixels[i].r != r->pixels[i].r || a.pixels[i].a != r->pixels[i].a;
        EXPECT_EQ(differ, 0) << r->stats.features.bvhWidth << "-wide";
    }
    EXPECT_GT(b.mean(0, 0, 0, 48, 48), 0.02);
}
