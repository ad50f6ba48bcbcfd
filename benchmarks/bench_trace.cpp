// bench_trace.cpp: ray throughput (issue 5). Primary, diffuse-bounce and shadow rays on
// the same procedural meshes, traced by RayDrive's intersect kernels on the chosen OpenCL
// device and by Embree 3 (rtcIntersect1/rtcOccluded1 over all cores; also its ray
// streams, rtcIntersect1M/rtcOccluded1M, and its watertight RTC_SCENE_FLAG_ROBUST mode) in the same run,
// median of several runs, reported as Mrays/s and as the ratio RayDrive / Embree; then
// the same rays through the treelet-streamed traversal (render/treelet_trace.h) at a few
// treelet budgets, resident and streamed through a cache, with their ratio to Embree and
// to the resident kernels.
#include <embree3/rtcore.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <random>
#include <thread>

#include "bench_inputs.h"
#include "bvh/collapse4.h"
#include "cl/include/ray.h"
#include "embree_peer.h"
#include "ocl/buffer.h"
#include "ocl/device.h"
#include "ocl/kernel.h"
#include "ocl/program.h"
#include "render/device_scene.h"
#include "render/sampling.h"
#include "render/scene_bvh.h"
#include "render/treelet_trace.h"

using namespace rd;
using Clock = std::chrono::steady_clock;

namespace {

// CPU seconds of the whole process (every thread): on a shared, loaded machine the
// ratio of CPU time is steadier than that of wall time, so both are printed.
double cpuSeconds() {
    timespec ts{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

// The median of the runs' own ratios num[r] / den[r]: each run times both within a few
// milliseconds, so a slow spell of the shared machine moves both sides of a ratio, where
// it moves one of two separate medians.
double pairedRatio(const std::vector<double>& num, const std::vector<double>& den) {
    std::vector<double> r(num.size());
    for (size_t i = 0; i < num.size(); ++i) r[i] = num[i] / den[i];
    return median(r);
}

// The command line (--help lists it)
struct BenchOptions {
    int runs = 5, side = 1024;
    std::string device, rayOrder = "tiles";
    std::vector<std::string> variants, meshFiles, onlyKinds;
    int sahBlock = 0, sahBins = 0, sahLeaf = 0;
    float sahTraversal = 0;
    bool wide8 = false, wide16 = false, noShadowPackets = false, noClosestPackets = false;
    std::string wide8Options, treeletOptions;
    std::vector<size_t> budgets{size_t(1) << 30, size_t(256) << 10, size_t(64) << 10,
                                size_t(4) << 10};
    double streamFraction = 0.25;
};

// The options, or the exit code where the command line asked for help or was wrong
std::optional<int> parseOptions(int argc, char** argv, BenchOptions& o) {
    CLI::App app{"RayDrive vs Embree: Mrays/s for primary, diffuse and shadow rays"};
    app.add_option("--runs", o.runs, "timed runs per measurement (median reported)");
    app.add_option("--side", o.side, "primary rays: side x side");
    app.add_option("--ray-order", o.rayOrder,
                   "primary rays' order: tiles (the renderer's: "
                   "16x16 tiles, Morton order within a tile; the default) or scanline")
        ->check(CLI::IsMember({"scanline", "tiles"}));
    app.add_option("--device", o.device, "OpenCL device (index or name)");
    app.add_flag(
        "--wide8", o.wide8,
        "also time the eight-wide BVH (float8 node tests; the default columns are "
        "the four-wide one)");
    app.add_option("--wide8-options", o.wide8Options,
                   "build options of the eight-wide kernels");
    app.add_flag(
        "--wide16", o.wide16,
        "also time the sixteen-wide BVH with the renderer's packets (float16 node "
        "tests: the renderer's tree on a device with AVX-512), a bvh16 line");
    app.add_option("--sah-block", o.sahBlock, "SAH block size (default: the renderer's)");
    app.add_option("--sah-bins", o.sahBins,
                   "SAH bins per axis (default: the renderer's)");
    app.add_option("--sah-leaf", o.sahLeaf,
                   "largest node always made a leaf (default: the renderer's)");
    app.add_option(
        "--sah-traversal", o.sahTraversal,
        "SAH traversal cost against one block's intersection (default: the renderer's)");
    app.add_option("--mesh", o.meshFiles, "also an OFF mesh (e.g. the Stanford bunny)");
    app.add_option(
        "--variant", o.variants,
        "extra OpenCL build options (e.g. -DRT_SOME_SWITCH): that kernel variant is "
        "timed in the same runs, printed against the default");
    app.add_option(
        "--treelet-options", o.treeletOptions,
        "extra build options of the treelet kernels (e.g. -DRT_TREELET_NEAREST_FIRST)");
    app.add_option("--treelet-budgets", o.budgets,
                   "treelet budgets in bytes to time (1 GiB and more: the whole BVH)");
    app.add_option(
        "--stream-fraction", o.streamFraction,
        "also stream 64 KiB treelets through a cache of this fraction of the BVH "
        "(0: not)");
    app.add_flag(
        "--no-shadow-packets", o.noShadowPackets,
        "--wide8: shadow rays one a work-item (the renderer's packets of eight are the "
        "default for triangle scenes)");
    app.add_flag("--no-closest-packets", o.noClosestPackets,
                 "--wide8: closest-hit rays one a work-item (likewise)");
    app.add_option("--kind", o.onlyKinds,
                   "time only these ray kinds (primary, diffuse, shadow; "
                   "e.g. under perf record)")
        ->check(CLI::IsMember({"primary", "diffuse", "shadow"}));
    bool noTreelets = false;
    app.add_flag("--no-treelets", noTreelets,
                 "time the resident kernels only (e.g. under perf record)");
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    }
    if (noTreelets) o.budgets.clear(), o.streamFraction = 0;
    return std::nullopt;
}

bool anyVariant(const BenchOptions& o, const char* macro) {
    return std::any_of(o.variants.begin(), o.variants.end(), [&](const std::string& v) {
        return v.find(macro) != std::string::npos;
    });
}

double msSince(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count() * 1e3;
}

// One mesh's trees: binary SAH, collapsed four-wide, and eight- and sixteen-wide where
// the options time them, with their build times.
struct MeshTrees {
    BvhBuildSettings bs = sceneBvhSettings();
    Bvh bvh;
    Bvh4 bvh4;
    Bvh8 bvh8;
    Bvh16 bvh16;
    double binaryMs = 0, collapseMs = 0, collapse16Ms = 0;
    bool need8 = false, need16 = false;

    void describe(const std::string& name, double embreeBuildMs) const {
        if (need16)
            std::printf(
                "%s: %zu sixteen-wide nodes (%.0f%% of slots used), collapse %.0f ms\n",
                name.c_str(), bvh16.nodes.size(), 100 * usedSlots(bvh16), collapse16Ms);
        std::printf(
            "%s: SAH cost %.2f, %zu four-wide nodes (%.0f%% of slots used), %zu "
            "eight-wide nodes (%.0f%%), %zu blocks\n",
            name.c_str(), bvhSahCost(bvh, bs.traversalCost, bs.intersectionCost),
            bvh4.nodes.size(), 100 * usedSlots(bvh4), bvh8.nodes.size(),
            100 * usedSlots(bvh8), bvh4.blocks.size());
        if (need8)  // (one build each: a rough figure on a noisy machine)
            std::printf(
                "%s: build %.0f ms (binary SAH %.0f + eight-wide collapse %.0f), "
                "Embree's %.0f ms (rtcCommitScene)\n",
                name.c_str(), binaryMs + collapseMs, binaryMs, collapseMs, embreeBuildMs);
    }
};

MeshTrees buildTrees(const Mesh& mesh, const BenchOptions& o) {
    MeshTrees t;
    if (o.sahBlock > 0) t.bs.blockSize = o.sahBlock;
    if (o.sahBins > 0) t.bs.binCount = o.sahBins;
    if (o.sahLeaf > 0) t.bs.maxLeafSize = o.sahLeaf;
    if (o.sahTraversal > 0) t.bs.traversalCost = o.sahTraversal;
    Scene s;
    s.triangles = mesh.tris;
    const std::vector<Aabb> bounds = triangleBounds(s);
    auto t0 = Clock::now();
    t.bvh = buildBvh(bounds, t.bs);
    t.binaryMs = msSince(t0);
    t.bvh4 = collapseToBvh4(t.bvh, mesh.tris);
    // the eight-wide tree for --wide8 and for variants built with -DRT_BVH8
    t.need8 = o.wide8 || anyVariant(o, "RT_BVH8");
    t0 = Clock::now();
    if (t.need8) t.bvh8 = collapseToBvh8(t.bvh, mesh.tris);
    t.collapseMs = msSince(t0);
    t.need16 = anyVariant(o, "RT_BVH16");
    t0 = Clock::now();
    if (t.need16) t.bvh16 = collapseToBvh16(t.bvh, mesh.tris);
    t.collapse16Ms = msSince(t0);
    return t;
}

// The trees' nodes and blocks on the device (those not timed: empty)
struct DeviceTrees {
    DeviceBuffer<Bvh4Node> nodes;
    DeviceBuffer<Triangle4> blocks;
    DeviceBuffer<Bvh8Node> nodes8;
    DeviceBuffer<Triangle4> blocks8;
    DeviceBuffer<Bvh16Node> nodes16;
    DeviceBuffer<Triangle4> blocks16;
    DeviceTrees(ClContext& ctx, const MeshTrees& t)
        : nodes(ctx, t.bvh4.nodes),
          blocks(ctx, t.bvh4.blocks),
          nodes8(ctx, t.bvh8.nodes.size()),
          blocks8(ctx, t.bvh8.blocks.size()),
          nodes16(ctx, std::max<size_t>(1, t.bvh16.nodes.size())),
          blocks16(ctx, std::max<size_t>(1, t.bvh16.blocks.size())) {
        if (t.need8) nodes8.upload(t.bvh8.nodes), blocks8.upload(t.bvh8.blocks);
        if (t.need16) nodes16.upload(t.bvh16.nodes), blocks16.upload(t.bvh16.blocks);
    }
};

// One ray kind's rays on one mesh, and what the resident kernels made of them
struct TreeletRays {
    const std::string& mesh;
    const char* kind;
    bool shadow;
    size_t n;
    DeviceBuffer<rt_float4>&org, &dir;
    DeviceBuffer<RayState>& state;
    const std::vector<RayState>& initialState;
    DeviceBuffer<RayHit>& hits;
    std::vector<RayHit> residentHits;
    std::vector<rt_float4> residentShadow;
    double residentMrays, embreeMrays;
};

// The rays through the treelet-streamed traversal at each budget, streamed through a
// cache of --stream-fraction of the tree, and on the eight-wide tree's cut (where
// `treelet8`): a row each for the table printed after the resident one. "agree" is
// bit-for-bit agreement with the resident kernels (hit, t, u, v; occlusion).
void timeTreelets(ClContext& ctx, Profiler& prof, const BenchOptions& o, Program& treelet,
                  Program* treelet8, const Bvh4& bvh4, const Bvh8& bvh8,
                  const TraceScene& sc, const TreeletRays& r,
                  std::vector<std::string>& rows) {
    struct Mode {
        size_t budget, memory;  // scene memory: 0, resident
        bool eight;             // the eight-wide tree's cut
    };
    std::vector<Mode> modes;
    for (size_t b : o.budgets) modes.push_back({b, 0, false});
    if (o.streamFraction > 0)
        modes.push_back(
            {size_t(64) << 10,
             std::max<size_t>(1, size_t(o.streamFraction *
                                        double(bvh4.nodes.size() * sizeof(Bvh4Node) +
                                               bvh4.blocks.size() * sizeof(Triangle4)))),
             false});
    if (treelet8)
        for (size_t b : o.budgets) modes.push_back({b, 0, true});
    const size_t n = r.n;
    for (auto [budget, memory, eight] : modes) {
        TreeletStats ts;
        std::unique_ptr<TreeletTracer> tracerOf =
            eight ? std::make_unique<TreeletTracer>(ctx, treelet8->get(), prof, bvh8,
                                                    budget, memory, n, ts)
                  : std::make_unique<TreeletTracer>(ctx, treelet.get(), prof, bvh4,
                                                    budget, memory, n, ts);
        TreeletTracer& tracer = *tracerOf;
        const std::vector<float> onesFlat(4 * n, 1.0f);  // RGB weights: 4 floats a ray
        DeviceBuffer<float> treeletWeight(ctx, onesFlat, CL_MEM_READ_WRITE);
        auto runTreelets = [&] {
            r.state.upload(r.initialState);
            treeletWeight.upload(onesFlat);
            ctx.finish();
            auto t0 = Clock::now();
            if (r.shadow)
                tracer.shadow(cl_uint(n), r.org, r.dir, r.state, treeletWeight, sc, 1);
            else
                tracer.closest(cl_uint(n), r.org, r.dir, r.state, r.hits, sc);
            ctx.finish();
            return std::chrono::duration<double>(Clock::now() - t0).count();
        };
        runTreelets();
        const TreeletStats once = ts;
        std::vector<double> tt;
        for (int i = 0; i < o.runs; ++i) tt.push_back(runTreelets());
        size_t agree = 0;
        if (r.shadow) {
            auto w2 = treeletWeight.download();
            for (size_t i = 0; i < n; ++i)
                agree += (w2[4 * i] == 0.0f) == (r.residentShadow[i].x == 0.0f);
        } else {
            auto h2 = r.hits.download();
            const std::vector<RayHit>& rh = r.residentHits;
            for (size_t i = 0; i < n; ++i)
                agree += h2[i].prim == rh[i].prim && h2[i].t == rh[i].t &&
                         h2[i].u == rh[i].u && h2[i].v == rh[i].v;
        }
        double mt = n / median(tt) * 1e-6;
        char label[64], row[320];
        if (budget >= (size_t(1) << 30))
            std::snprintf(label, sizeof label, "whole%s", eight ? " 8" : "");
        else
            std::snprintf(label, sizeof label, "%zuK%s%s", budget >> 10,
                          memory ? " stream" : "", eight ? " 8" : "");
        std::snprintf(
            row, sizeof row,
            "%-14s %-8s %-11s %8zu %7llu %10llu %8llu %10.2f %8.3f %8.3f %8.4f%%",
            r.mesh.c_str(), r.kind, label, ts.treelets, (unsigned long long)once.rounds,
            (unsigned long long)once.pairs, (unsigned long long)once.uploads, mt,
            mt / r.embreeMrays, mt / r.residentMrays, 100.0 * double(agree) / double(n));
        rows.push_back(row);
    }
}

}  // namespace

int benchMain(int argc, char** argv) {
    BenchOptions o;
    if (std::optional<int> exit = parseOptions(argc, argv, o)) return *exit;

    ClContext ctx(selectDevice(o.device));
    std::printf(
        "device: %s | Embree %d.%d.%d on %u threads | median of %d runs | primary "
        "rays in %s order\n",
        ctx.name().c_str(), RTC_VERSION_MAJOR, RTC_VERSION_MINOR, RTC_VERSION_PATCH,
        std::thread::hardware_concurrency(), o.runs, o.rayOrder.c_str());
    // The kernels as a scene whose shaders trace in sampled directions builds them
    // (RT_INCOHERENT_TRACE): the diffuse rays, bounces, walk their nodes' hit masks.
    const std::string base = "-cl-std=CL1.2 -DRT_INCOHERENT_TRACE ";
    // --wide16 is the variant of the sixteen-wide tree with the eight-wide line's packets
    const std::string wide16Variant =
        std::string("-DRT_BVH16 ") + (o.noShadowPackets ? "" : "-DRT_SHADOW_PACKETS ") +
        (o.noClosestPackets ? "" : "-DRT_CLOSEST_PACKETS ") + o.wide8Options;
    if (o.wide16) o.variants.insert(o.variants.begin(), wide16Variant);
    std::vector<std::unique_ptr<Program>> programs;
    programs.push_back(std::make_unique<Program>(ctx, assembleClSource({"intersect.cl"}), base));
    for (const std::string& v : o.variants)
        programs.push_back(
            std::make_unique<Program>(ctx, assembleClSource({"intersect.cl"}), base + v));
    Program treeletProgram(
        ctx, assembleClSource({"intersect.cl", "treelet.cl"}),
        "-cl-std=CL1.2 -DRT_HAS_TREELETS -DRT_HAS_INT64_MIN " + o.treeletOptions);
    // (--wide8: the treelets of the eight-wide tree too, "8" in the budget column)
    std::unique_ptr<Program> treeletProgram8;
    if (o.wide8 && !o.budgets.empty())
        treeletProgram8 = std::make_unique<Program>(
            ctx, assembleClSource({"intersect.cl", "treelet.cl"}),
            "-cl-std=CL1.2 -DRT_HAS_TREELETS -DRT_HAS_INT64_MIN -DRT_BVH8 " +
                o.treeletOptions);
    std::vector<std::string> treeletRows;  // printed after the resident table
    std::printf("%-14s %-8s %10s %10s %10s %8s %9s %9s\n", "scene", "rays", "count",
                "RayDrive", "Embree", "ratio", "agree", "cpu ratio");
    // the renderer's packets for a triangle scene on the eight-wide tree
    const std::string packetOptions =
        std::string(o.noShadowPackets ? "" : "-DRT_SHADOW_PACKETS ") +
        (o.noClosestPackets ? "" : "-DRT_CLOSEST_PACKETS ");
    std::unique_ptr<Program> program8;
    if (o.wide8)
        program8 = std::make_unique<Program>(
            ctx, assembleClSource({"intersect.cl"}),
            base + "-DRT_BVH8 " + packetOptions + o.wide8Options);
    // work-items of a kernel for n rays (to one light): RT_PACKET_RAYS each where
    // the program was built with that kernel's packets (`macro`)
    auto items = [](size_t n, const std::string& options, const char* macro) {
        return options.find(macro) == std::string::npos
                   ? n
                   : (n + RT_PACKET_RAYS - 1) / RT_PACKET_RAYS;
    };
    const std::string options8 = o.wide8 ? packetOptions + o.wide8Options : "";
    std::vector<Mesh> meshes{sphereField(300, 250, "75k-tris"), sphereField(2000, 500, "1M-tris")};
    for (const std::string& f : o.meshFiles) meshes.push_back(loadOff(f));
    for (const Mesh& mesh : meshes) {
        const MeshTrees host = buildTrees(mesh, o);
        EmbreeScene emb(mesh), embRobust(mesh, true);
        host.describe(mesh.name, emb.buildMs);
        const DeviceTrees trees(ctx, host);
        const Bvh4& bvh4 = host.bvh4;
        const Bvh8& bvh8 = host.bvh8;
        // the object, motion and sample buffers the kernels take; unused for a triangle
        // scene built without RT_HAS_QUADRICS and RT_HAS_MOTION
        DeviceBuffer<Quadric> noQuadrics(ctx, 1);
        DeviceBuffer<uint32_t> noCsg(ctx, 1), noSample(ctx, 1);
        DeviceBuffer<Triangle> noTris(ctx, 1);
        DeviceBuffer<rt_float4> noMotion(ctx, 1);
        DeviceBuffer<float> noTime(ctx, 1);
        DeviceBuffer<uint32_t> noNumerics(ctx, 1);  // archive flags: RT_HAS_PROCEDURALS only
        Rays primary = primaryRays(o.side, o.rayOrder);
        std::vector<RayHit> primHits;
        emb.trace(primary, false, primHits);
        Rays diffuse = secondaryRays(mesh, primary, primHits, false);
        Rays shadow = secondaryRays(mesh, primary, primHits, true);
        struct Kind {
            const char* name;
            const Rays* rays;
            bool shadow;
        } kinds[] = {{"primary", &primary, false}, {"diffuse", &diffuse, false},
                     {"shadow", &shadow, true}};
        for (const Kind& k : kinds) {
            if (!o.onlyKinds.empty() && std::find(o.onlyKinds.begin(), o.onlyKinds.end(),
                                                  k.name) == o.onlyKinds.end())
                continue;
            size_t n = k.rays->org.size();
            DeviceBuffer<rt_float4> org(ctx, k.rays->org), dir(ctx, k.rays->dir);
            // diffuse rays are bounces (trace depth 1: the kernels walk their nodes' hit
            // masks); primary and shadow rays are coherent (the lane walk)
            const uint32_t depth = k.rays == &diffuse ? 1u : 0u;
            std::vector<RayState> st(n, RayState{1u, depth, RT_NO_HIT, 0u});
            DeviceBuffer<RayState> state(ctx, st, CL_MEM_READ_WRITE);
            // the resident shadow kernel zeroes an occluded ray's weight (all ones here)
            const std::vector<rt_float4> ones(n, rt_float4{1.0f, 1.0f, 1.0f, 1.0f});
            DeviceBuffer<rt_float4> weight(ctx, ones, CL_MEM_READ_WRITE);
            DeviceBuffer<RayHit> hits(ctx, n);
            Profiler prof(ctx);
            std::vector<std::unique_ptr<Kernel>> kcs, kss;
            for (const auto& prog : programs) {
                kcs.push_back(std::make_unique<Kernel>(ctx, prog->get(), "intersect_closest", prof));
                kss.push_back(std::make_unique<Kernel>(ctx, prog->get(), "intersect_shadow", prof));
            }
            // a variant built with -DRT_BVH8 walks the eight-wide tree (needs --wide8)
            auto eightWide = [&](size_t p) {
                return p > 0 && o.variants[p - 1].find("RT_BVH8") != std::string::npos;
            };
            auto sixteenWide = [&](size_t p) {
                return p > 0 && o.variants[p - 1].find("RT_BVH16") != std::string::npos;
            };
            auto runDevice = [&](size_t p) {
                auto run = [&](auto& nodeBuf, auto& blockBuf) {
                    Kernel& kc = *kcs[p];
                    Kernel& ks = *kss[p];
                    if (k.shadow) {
                        weight.upload(ones);
                        auto t0 = Clock::now();
                        ks.launch(items(n, p > 0 ? o.variants[p - 1] : std::string(),
                                        "RT_SHADOW_PACKETS"),
                                  cl_uint(n), nodeBuf, blockBuf, org, dir, state, weight,
                                  noQuadrics, noCsg, noTris, noMotion, noTris, noSample,
                                  noTime, cl_uint(1), noNumerics, noNumerics, noNumerics,
                                  noNumerics, noNumerics,
                                  noNumerics);  // (opaque shadows)
                        ctx.finish();
                        return std::chrono::duration<double>(Clock::now() - t0).count();
                    }
                    auto t0 = Clock::now();
                    kc.launch(items(n, p > 0 ? o.variants[p - 1] : std::string(),
                                    "RT_CLOSEST_PACKETS"),
                              cl_uint(n), nodeBuf, blockBuf, org, dir, state, hits,
                              noQuadrics, noCsg, noTris, noMotion, noTris, noSample,
                              noTime, noSample);
                    ctx.finish();
                    return std::chrono::duration<double>(Clock::now() - t0).count();
                };
                if (sixteenWide(p)) return run(trees.nodes16, trees.blocks16);
                return eightWide(p) ? run(trees.nodes8, trees.blocks8)
                                    : run(trees.nodes, trees.blocks);
            };
            std::unique_ptr<Kernel> kc8, ks8;
            DeviceBuffer<RayHit> hits8(ctx, n);
            DeviceBuffer<RayState> state8(ctx, st, CL_MEM_READ_WRITE);
            DeviceBuffer<rt_float4> weight8(ctx, ones, CL_MEM_READ_WRITE);
            if (o.wide8) {
                kc8 = std::make_unique<Kernel>(ctx, program8->get(), "intersect_closest", prof);
                ks8 = std::make_unique<Kernel>(ctx, program8->get(), "intersect_shadow", prof);
            }
            auto runWide8 = [&] {
                if (k.shadow) weight8.upload(ones);
                auto t0 = Clock::now();
                if (k.shadow)
                    ks8->launch(items(n, options8, "RT_SHADOW_PACKETS"), cl_uint(n),
                                trees.nodes8, trees.blocks8, org, dir, state8, weight8,
                                noQuadrics, noCsg, noTris, noMotion, noTris, noSample,
                                noTime, cl_uint(1), noNumerics, noNumerics, noNumerics,
                                noNumerics, noNumerics, noNumerics);  // (opaque shadows)
                else
                    kc8->launch(items(n, options8, "RT_CLOSEST_PACKETS"), cl_uint(n),
                                trees.nodes8, trees.blocks8, org, dir, state8, hits8,
                                noQuadrics, noCsg, noTris, noMotion, noTris, noSample,
                                noTime, noSample);
                ctx.finish();
                return std::chrono::duration<double>(Clock::now() - t0).count();
            };
            std::vector<double> t8;
            if (o.wide8) runWide8();
            std::vector<std::vector<double>> tv(programs.size());
            for (size_t p = programs.size(); p-- > 0;) runDevice(p);  // PoCL compiles on first launch
            std::vector<double> td, te, cd, ce, tes, ter;
            std::vector<RayHit> eh, ehs, ehr;
            auto timed = [](auto&& f) {
                auto t0 = Clock::now();
                f();
                return std::chrono::duration<double>(Clock::now() - t0).count();
            };
            const bool coherent = k.rays == &primary;
            // Each timing follows an untimed run of the same kernel or Embree call, so that
            // every one starts with its own tree in the caches: without it a kernel timed
            // after another on the same tree started warm and the first one cold (on the
            // 75k field's 7 ms of diffuse rays, a variant read ~4% faster in second place).
            for (int r = 0; r < o.runs; ++r) {
                for (size_t p = 1; p < programs.size(); ++p) {
                    runDevice(p);
                    tv[p].push_back(runDevice(p));
                }
                if (o.wide8) {
                    runWide8();
                    t8.push_back(runWide8());
                }
                runDevice(0);
                double c0 = cpuSeconds();
                td.push_back(runDevice(0));
                cd.push_back(cpuSeconds() - c0);
                emb.trace(*k.rays, k.shadow, eh);
                double c1 = cpuSeconds();
                auto t0 = Clock::now();
                emb.trace(*k.rays, k.shadow, eh);
                te.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
                ce.push_back(cpuSeconds() - c1);
                emb.trace(*k.rays, k.shadow, ehs, true, coherent);
                tes.push_back(timed([&] { emb.trace(*k.rays, k.shadow, ehs, true, coherent); }));
                embRobust.trace(*k.rays, k.shadow, ehr);
                ter.push_back(timed([&] { embRobust.trace(*k.rays, k.shadow, ehr); }));
            }
            // Agreement: same hit / same occlusion as Embree.
            size_t same = 0;
            if (k.shadow) {
                auto w2 = weight.download();
                for (size_t i = 0; i < n; ++i)
                    same += (w2[i].x == 0.0f) == (eh[i].prim != RT_NO_HIT);
            } else {
                auto h2 = hits.download();
                for (size_t i = 0; i < n; ++i)
                    same += (h2[i].prim == RT_NO_HIT) == (eh[i].prim == RT_NO_HIT) &&
                            (h2[i].prim == RT_NO_HIT || std::fabs(h2[i].t - eh[i].t) <=
                                                             1e-3f * std::max(1.0f, eh[i].t));
            }
            double md = n / median(td) * 1e-6, me = n / median(te) * 1e-6;
            std::printf("%-14s %-8s %10zu %10.2f %10.2f %8.3f %8.4f%% %9.3f\n", mesh.name.c_str(),
                        k.name, n, md, me, md / me, 100.0 * double(same) / double(n),
                        median(ce) / median(cd));
            std::printf("  Embree stream (rtc%s1M) %13.2f Mrays/s; robust (watertight) "
                        "rtc%s1 %.2f Mrays/s; RayDrive / robust %.3f\n",
                        k.shadow ? "Occluded" : "Intersect", n / median(tes) * 1e-6,
                        k.shadow ? "Occluded" : "Intersect", n / median(ter) * 1e-6,
                        median(ter) / median(td));
            if (o.wide8) {
                size_t same8 = 0;
                auto h8 = hits8.download();
                auto w8 = weight8.download();
                for (size_t i = 0; i < n; ++i)
                    same8 += k.shadow ? (w8[i].x == 0.0f) == (eh[i].prim != RT_NO_HIT)
                                      : (h8[i].prim == RT_NO_HIT) == (eh[i].prim == RT_NO_HIT) &&
                                            (h8[i].prim == RT_NO_HIT ||
                                             std::fabs(h8[i].t - eh[i].t) <=
                                                 1e-3f * std::max(1.0f, eh[i].t));
                std::printf("  bvh8 %-33s %10.2f Mrays/s, %.3f of bvh4, %.3f of Embree, agree "
                            "%.4f%%; %.3f of Embree stream, %.3f of Embree robust\n", "",
                            n / median(t8) * 1e-6, median(td) / median(t8),
                            median(te) / median(t8), 100.0 * double(same8) / double(n),
                            median(tes) / median(t8), median(ter) / median(t8));
            }
            for (size_t p = 1; p < programs.size(); ++p) {
                const bool is16 = o.wide16 && p == 1;
                const std::string label = is16 ? "bvh16" : "variant " + o.variants[p - 1];
                std::printf("  %-38s %10.2f Mrays/s, %.3f of default, %.3f of Embree (paired %.3f)",
                            label.c_str(), n / median(tv[p]) * 1e-6, median(td) / median(tv[p]),
                            median(te) / median(tv[p]), pairedRatio(te, tv[p]));
                if (o.wide8) std::printf(", %.3f of bvh8", median(t8) / median(tv[p]));
                std::printf("; %.3f of Embree stream, %.3f of Embree robust\n",
                            median(tes) / median(tv[p]), median(ter) / median(tv[p]));
            }
            std::fflush(stdout);
            // The treelet path on the same rays
            DeviceBuffer<Triangle> tris(ctx, mesh.tris);
            const TraceScene sc{noQuadrics, noCsg, tris, noMotion, tris, noSample, noTime};
            const TreeletRays tr{
                mesh.name, k.name,          k.shadow,          n,  org, dir, state, st,
                hits,      hits.download(), weight.download(), md, me};
            timeTreelets(ctx, prof, o, treeletProgram, treeletProgram8.get(), bvh4, bvh8,
                         sc, tr, treeletRows);
        }
    }
    std::printf("(Mrays/s, wall time of one launch over all rays incl. launch overhead;\n"
                " cpu ratio: Embree's CPU seconds over RayDrive's for the same rays)\n\n");
    std::printf("treelet-streamed traversal (rounds, pairs, uploads: of one trace; agree: "
                "bit for bit with the resident kernels)\n");
    std::printf("%-14s %-8s %-11s %8s %7s %10s %8s %10s %8s %8s %9s\n", "scene", "rays",
                "budget", "treelets", "rounds", "pairs", "uploads", "Mrays/s", "/Embree",
                "/resid.", "agree");
    for (const std::string& r : treeletRows) std::printf("%s\n", r.c_str());
    return 0;
}

// A kernel variant that does not build, a mesh that cannot be read, an OpenCL error:
// a message and a non-zero exit, not an abort.
int main(int argc, char** argv) {
    try {
        return benchMain(argc, argv);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "bench_trace: %s\n", e.what());
        return 1;
    }
}
