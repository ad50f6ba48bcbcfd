// bench_trace.cpp: ray throughput (issue 5). Primary, diffuse-bounce and shadow rays on
// the same procedural meshes, traced by RayDrive's intersect kernels on the chosen OpenCL
// device and by Embree 3 (rtcIntersect1/rtcOccluded1 over all cores; also its ray
// streams, rtcIntersect1M/rtcOccluded1M, and its watertight RTC_SCENE_FLAG_ROBUST mode) in the same run,
// median of several runs, reported as Mrays/s and as the ratio RayDrive / Embree; then
// the same rays through the treelet-streamed traversal (render/treelet_trace.h) at a few
// treelet budgets, resident and streamed through a cache, with their ratio to Embree and
// to the resident kernels.
#include <embree3/rtcore.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <thread>

#include <CLI/CLI.hpp>

#include "bvh/collapse4.h"
#include "cl/include/ray.h"
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

struct Mesh {
    std::vector<Triangle> tris;
    std::string name;
};

// A field of `count` spheres, each diced into about `perSphere` triangles, scattered in a
// 10x10x10 box: many objects, open space between them, as a scene has.
Mesh sphereField(int count, int perSphere, const std::string& name) {
    Mesh m{{}, name};
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0, 1);
    int nu = std::max(4, int(std::sqrt(perSphere / 2.0)) * 1), nv = std::max(3, perSphere / (2 * nu));
    for (int s = 0; s < count; ++s) {
        float cx = 10 * u(rng) - 5, cy = 10 * u(rng) - 5, cz = 10 * u(rng) - 5;
        float r = 0.05f + 0.4f * u(rng) * u(rng);
        auto P = [&](int i, int j) {
            float th = 2 * float(M_PI) * i / nu, ph = float(M_PI) * j / nv - float(M_PI) / 2;
            return rt_float4{cx + r * std::cos(ph) * std::cos(th),
                             cy + r * std::cos(ph) * std::sin(th), cz + r * std::sin(ph), 0};
        };
        for (int j = 0; j < nv; ++j)
            for (int i = 0; i < nu; ++i) {
                m.tris.push_back({P(i, j), P(i + 1, j), P(i + 1, j + 1)});
                m.tris.push_back({P(i, j), P(i + 1, j + 1), P(i, j + 1)});
            }
    }
    return m;
}

// A triangle mesh from an OFF file (polygons fanned into triangles), scaled and centred
// into the same 10x10x10 box, e.g. the Stanford bunny from Debian's libcgal-demo
// (run_trace.sh fetches it; it is not ours to commit).
Mesh loadOff(const std::string& path) {
    std::ifstream in(path);
    std::string word;
    auto next = [&]() -> std::string {  // the next token, comments skipped
        while (in >> word) {
            if (word[0] != '#') return word;
            std::getline(in, word);
        }
        throw std::runtime_error(path + ": truncated OFF file");
    };
    if (!in || next() != "OFF") throw std::runtime_error(path + ": not an OFF file");
    const size_t nv = std::stoul(next()), nf = std::stoul(next());
    next();  // edges
    std::vector<rt_float4> v(nv);
    float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
    for (rt_float4& p : v) {
        p = {std::stof(next()), std::stof(next()), std::stof(next()), 0};
        const float c[3] = {p.x, p.y, p.z};
        for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], c[a]), hi[a] = std::max(hi[a], c[a]);
    }
    const float scale = 10.0f / std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
    for (rt_float4& p : v)
        p = {(p.x - 0.5f * (lo[0] + hi[0])) * scale, -(p.y - 0.5f * (lo[1] + hi[1])) * scale,
             (p.z - 0.5f * (lo[2] + hi[2])) * scale, 0};
    Mesh m{{}, std::filesystem::path(path).stem().string()};
    for (size_t f = 0; f < nf; ++f) {
        const size_t k = std::stoul(next());
        std::vector<size_t> idx(k);
        for (size_t& i : idx) {
            i = std::stoul(next());
            if (i >= nv) throw std::runtime_error(path + ": vertex index out of range");
        }
        for (size_t j = 1; j + 1 < k; ++j) m.tris.push_back({v[idx[0]], v[idx[j]], v[idx[j + 1]]});
    }
    return m;
}

struct Rays {
    std::vector<rt_float4> org, dir;  // w: tmin, tmax
};

// Primary rays through side x side pixels, in the order the renderer samples them
// (rd::tileOrder: 16x16 tiles, Morton order within a tile) or in scanline order.
Rays primaryRays(int side, const std::string& order) {
    Rays r;
    std::vector<uint32_t> pixels = rd::tileOrder(side, 0, side, 0, side);
    if (order == "scanline") std::sort(pixels.begin(), pixels.end());
    for (uint32_t pixel : pixels) {
        const int x = int(pixel % uint32_t(side)), y = int(pixel / uint32_t(side));
        float sx = (x + 0.5f) / side * 2 - 1, sy = (y + 0.5f) / side * 2 - 1;
        float len = std::sqrt(sx * sx * 0.36f + sy * sy * 0.36f + 1);
        r.org.push_back({0, 0, -16, 0});
        r.dir.push_back({sx * 0.6f / len, sy * 0.6f / len, 1 / len, 1e30f});
    }
    return r;
}

struct EmbreeScene {
    RTCDevice device;
    RTCScene scene;
    // robust: RTC_SCENE_FLAG_ROBUST, Embree's watertight mode (its default is not)
    explicit EmbreeScene(const Mesh& m, bool robust = false) {
        // (Embree's default configuration: its set_affinity=1, tried beside PoCL's pinned
        // threads, halved its Mrays/s on the 2-core development machine)
        device = rtcNewDevice(nullptr);
        scene = rtcNewScene(device);
        if (robust) rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
        RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
        float* v = (float*)rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0,
                                                   RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                   3 * m.tris.size());
        unsigned* idx = (unsigned*)rtcSetNewGeometryBuffer(
            g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), m.tris.size());
        for (size_t t = 0; t < m.tris.size(); ++t) {
            const rt_float4* p[3] = {&m.tris[t].v0, &m.tris[t].v1, &m.tris[t].v2};
            for (int k = 0; k < 3; ++k) {
                v[9 * t + 3 * k] = p[k]->x;
                v[9 * t + 3 * k + 1] = p[k]->y;
                v[9 * t + 3 * k + 2] = p[k]->z;
                idx[3 * t + k] = unsigned(3 * t + k);
            }
        }
        rtcCommitGeometry(g);
        rtcAttachGeometry(scene, g);
        rtcReleaseGeometry(g);
        const auto t0 = Clock::now();
        rtcCommitScene(scene);
        buildMs = std::chrono::duration<double>(Clock::now() - t0).count() * 1e3;
    }
    double buildMs = 0;  // rtcCommitScene: the BVH build
    ~EmbreeScene() {
        rtcReleaseScene(scene);
        rtcReleaseDevice(device);
    }
    // Closest hits (t, prim) or occlusion, over all hardware threads, each a contiguous
    // share of the rays (as PoCL's work-groups take them): one rtcIntersect1 or
    // rtcOccluded1 per ray, or with `stream` one rtcIntersect1M / rtcOccluded1M call per
    // thread (`coherent`: the coherent-stream hint, for primary rays).
    void trace(const Rays& r, bool shadow, std::vector<RayHit>& out, bool stream = false,
               bool coherent = false) const {
        out.resize(r.org.size());
        const size_t n = r.org.size();
        unsigned nt = std::max(1u, std::thread::hardware_concurrency());
        std::vector<std::thread> th;
        for (unsigned t = 0; t < nt; ++t)
            th.emplace_back([&, t] {
                RTCIntersectContext ctx;
                rtcInitIntersectContext(&ctx);
                if (stream)
                    ctx.flags = coherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT
                                         : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
                const size_t b = n * t / nt, e = n * (t + 1) / nt;
                auto ray = [&](size_t i) {
                    RTCRayHit rh;
                    rh.ray.org_x = r.org[i].x, rh.ray.org_y = r.org[i].y, rh.ray.org_z = r.org[i].z;
                    rh.ray.dir_x = r.dir[i].x, rh.ray.dir_y = r.dir[i].y, rh.ray.dir_z = r.dir[i].z;
                    rh.ray.tnear = r.org[i].w, rh.ray.tfar = r.dir[i].w;
                    rh.ray.mask = ~0u, rh.ray.flags = 0, rh.ray.time = 0, rh.ray.id = unsigned(i);
                    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
                    return rh;
                };
                auto result = [&](size_t i, const RTCRayHit& rh) {
                    if (shadow) {
                        out[i].prim = rh.ray.tfar < 0 ? 0 : RT_NO_HIT;
                    } else {
                        out[i].t = rh.ray.tfar;
                        out[i].prim = rh.hit.geomID == RTC_INVALID_GEOMETRY_ID ? RT_NO_HIT
                                                                                : rh.hit.primID;
                    }
                };
                if (stream) {
                    std::vector<RTCRayHit> rays(e - b);
                    for (size_t i = b; i < e; ++i) rays[i - b] = ray(i);
                    if (shadow)
                        rtcOccluded1M(scene, &ctx, &rays[0].ray, unsigned(e - b),
                                      sizeof(RTCRayHit));
                    else
                        rtcIntersect1M(scene, &ctx, rays.data(), unsigned(e - b),
                                       sizeof(RTCRayHit));
                    for (size_t i = b; i < e; ++i) result(i, rays[i - b]);
                    return;
                }
                for (size_t i = b; i < e; ++i) {
                    RTCRayHit rh = ray(i);
                    if (shadow) rtcOccluded1(scene, &ctx, &rh.ray);
                    else rtcIntersect1(scene, &ctx, &rh);
                    result(i, rh);
                }
            });
        for (auto& t : th) t.join();
    }
};

// Secondary rays from the primary hits: cosine-ish random directions (diffuse) or toward
// a point light (shadow). Rays whose primary ray missed are left out.
Rays secondaryRays(const Mesh& m, const Rays& prim, const std::vector<RayHit>& hits,
                   bool shadow) {
    Rays r;
    std::mt19937 rng(11);
    std::normal_distribution<float> g;
    const rt_float4 light{20, 30, -20, 0};
    for (size_t i = 0; i < hits.size(); ++i) {
        if (hits[i].prim == RT_NO_HIT) continue;
        const Triangle& t = m.tris[hits[i].prim];
        float px = prim.org[i].x + hits[i].t * prim.dir[i].x;
        float py = prim.org[i].y + hits[i].t * prim.dir[i].y;
        float pz = prim.org[i].z + hits[i].t * prim.dir[i].z;
        float ex = t.v1.x - t.v0.x, ey = t.v1.y - t.v0.y, ez = t.v1.z - t.v0.z;
        float fx = t.v2.x - t.v0.x, fy = t.v2.y - t.v0.y, fz = t.v2.z - t.v0.z;
        float nx = ey * fz - ez * fy, ny = ez * fx - ex * fz, nz = ex * fy - ey * fx;
        float nl = std::sqrt(nx * nx + ny * ny + nz * nz);
        nx /= nl, ny /= nl, nz /= nl;
        if (nx * prim.dir[i].x + ny * prim.dir[i].y + nz * prim.dir[i].z > 0)
            nx = -nx, ny = -ny, nz = -nz;
        float dx, dy, dz, tmax = 1e30f;
        if (shadow) {
            dx = light.x - px, dy = light.y - py, dz = light.z - pz;
            tmax = std::sqrt(dx * dx + dy * dy + dz * dz);
            dx /= tmax, dy /= tmax, dz /= tmax;
            tmax *= 0.9999f;
        } else {
            dx = nx + g(rng), dy = ny + g(rng), dz = nz + g(rng);  // ~cosine lobe
            float l = std::sqrt(dx * dx + dy * dy + dz * dz);
            dx /= l, dy /= l, dz /= l;
        }
        r.org.push_back({px + 1e-4f * nx, py + 1e-4f * ny, pz + 1e-4f * nz, 0});
        r.dir.push_back({dx, dy, dz, tmax});
    }
    return r;
}

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

}  // namespace

int benchMain(int argc, char** argv) {
    CLI::App app{"RayDrive vs Embree: Mrays/s for primary, diffuse and shadow rays"};
    int runs = 5, side = 1024;
    std::string device;
    app.add_option("--runs", runs, "timed runs per measurement (median reported)");
    app.add_option("--side", side, "primary rays: side x side");
    std::string rayOrder = "tiles";
    app.add_option("--ray-order", rayOrder, "primary rays' order: tiles (the renderer's: "
                   "16x16 tiles, Morton order within a tile; the default) or scanline")
        ->check(CLI::IsMember({"scanline", "tiles"}));
    app.add_option("--device", device, "OpenCL device (index or name)");
    std::vector<std::string> variants, meshFiles;
    int sahBlock = 0, sahBins = 0, sahLeaf = 0;
    float sahTraversal = 0;
    bool wide8 = false;
    app.add_flag("--wide8", wide8,
                 "also time the eight-wide BVH (float8 node tests; the default columns are "
                 "the four-wide one)");
    std::string wide8Options;
    app.add_option("--wide8-options", wide8Options, "build options of the eight-wide kernels");
    bool wide16 = false;
    app.add_flag("--wide16", wide16,
                 "also time the sixteen-wide BVH with the renderer's packets (float16 node "
                 "tests: the renderer's tree on a device with AVX-512), a bvh16 line");
    app.add_option("--sah-block", sahBlock, "SAH block size (default: the renderer's)");
    app.add_option("--sah-bins", sahBins, "SAH bins per axis (default: the renderer's)");
    app.add_option("--sah-leaf", sahLeaf, "largest node always made a leaf (default: the renderer's)");
    app.add_option("--sah-traversal", sahTraversal,
                   "SAH traversal cost against one block's intersection (default: the renderer's)");
    app.add_option("--mesh", meshFiles, "also an OFF mesh (e.g. the Stanford bunny)");
    app.add_option("--variant", variants,
                   "extra OpenCL build options (e.g. -DRT_SOME_SWITCH): that kernel variant is "
                   "timed in the same runs, printed against the default");
    std::vector<size_t> budgets{size_t(1) << 30, size_t(256) << 10, size_t(64) << 10,
                                size_t(4) << 10};
    double streamFraction = 0.25;
    std::string treeletOptions;
    app.add_option("--treelet-options", treeletOptions,
                   "extra build options of the treelet kernels (e.g. -DRT_TREELET_NEAREST_FIRST)");
    app.add_option("--treelet-budgets", budgets,
                   "treelet budgets in bytes to time (1 GiB and more: the whole BVH)");
    app.add_option("--stream-fraction", streamFraction,
                   "also stream 64 KiB treelets through a cache of this fraction of the BVH "
                   "(0: not)");
    bool noShadowPackets = false, noClosestPackets = false;
    app.add_flag("--no-shadow-packets", noShadowPackets,
                 "--wide8: shadow rays one a work-item (the renderer's packets of eight are the "
                 "default for triangle scenes)");
    app.add_flag("--no-closest-packets", noClosestPackets,
                 "--wide8: closest-hit rays one a work-item (likewise)");
    std::vector<std::string> onlyKinds;
    app.add_option("--kind", onlyKinds, "time only these ray kinds (primary, diffuse, shadow; "
                                        "e.g. under perf record)")
        ->check(CLI::IsMember({"primary", "diffuse", "shadow"}));
    bool noTreelets = false;
    app.add_flag("--no-treelets", noTreelets,
                 "time the resident kernels only (e.g. under perf record)");
    CLI11_PARSE(app, argc, argv);
    if (noTreelets) budgets.clear(), streamFraction = 0;

    ClContext ctx(selectDevice(device));
    std::printf("device: %s | Embree %d.%d.%d on %u threads | median of %d runs | primary "
                "rays in %s order\n",
                ctx.name().c_str(), RTC_VERSION_MAJOR, RTC_VERSION_MINOR, RTC_VERSION_PATCH,
                std::thread::hardware_concurrency(), runs, rayOrder.c_str());
    // The kernels as a scene whose shaders trace in sampled directions builds them
    // (RT_INCOHERENT_TRACE): the diffuse rays, bounces, walk their nodes' hit masks.
    const std::string base = "-cl-std=CL1.2 -DRT_INCOHERENT_TRACE ";
    // --wide16 is the variant of the sixteen-wide tree with the eight-wide line's packets
    const std::string wide16Variant =
        std::string("-DRT_BVH16 ") + (noShadowPackets ? "" : "-DRT_SHADOW_PACKETS ") +
        (noClosestPackets ? "" : "-DRT_CLOSEST_PACKETS ") + wide8Options;
    if (wide16) variants.insert(variants.begin(), wide16Variant);
    std::vector<std::unique_ptr<Program>> programs;
    programs.push_back(std::make_unique<Program>(ctx, assembleClSource({"intersect.cl"}), base));
    for (const std::string& v : variants)
        programs.push_back(
            std::make_unique<Program>(ctx, assembleClSource({"intersect.cl"}), base + v));
    Program treeletProgram(ctx, assembleClSource({"intersect.cl", "treelet.cl"}),
                           "-cl-std=CL1.2 -DRT_HAS_TREELETS -DRT_HAS_INT64_MIN " + treeletOptions);
    // (--wide8: the treelets of the eight-wide tree too, "8" in the budget column)
    std::unique_ptr<Program> treeletProgram8;
    if (wide8 && !budgets.empty())
        treeletProgram8 = std::make_unique<Program>(
            ctx, assembleClSource({"intersect.cl", "treelet.cl"}),
            "-cl-std=CL1.2 -DRT_HAS_TREELETS -DRT_HAS_INT64_MIN -DRT_BVH8 " + treeletOptions);
    std::vector<std::string> treeletRows;  // printed after the resident table
    std::printf("%-14s %-8s %10s %10s %10s %8s %9s %9s\n", "scene", "rays", "count",
                "RayDrive", "Embree", "ratio", "agree", "cpu ratio");
    // the renderer's packets for a triangle scene on the eight-wide tree
    const std::string packetOptions =
        std::string(noShadowPackets ? "" : "-DRT_SHADOW_PACKETS ") +
        (noClosestPackets ? "" : "-DRT_CLOSEST_PACKETS ");
    std::unique_ptr<Program> program8;
    if (wide8)
        program8 = std::make_unique<Program>(ctx, assembleClSource({"intersect.cl"}),
                                             base + "-DRT_BVH8 " + packetOptions + wide8Options);
    // work-items of a kernel for n rays (to one light): RT_PACKET_RAYS each where
    // the program was built with that kernel's packets (`macro`)
    auto items = [](size_t n, const std::string& options, const char* macro) {
        return options.find(macro) == std::string::npos
                   ? n
                   : (n + RT_PACKET_RAYS - 1) / RT_PACKET_RAYS;
    };
    const std::string options8 = wide8 ? packetOptions + wide8Options : "";
    std::vector<Mesh> meshes{sphereField(300, 250, "75k-tris"), sphereField(2000, 500, "1M-tris")};
    for (const std::string& f : meshFiles) meshes.push_back(loadOff(f));
    for (const Mesh& mesh : meshes) {
        BvhBuildSettings bs = sceneBvhSettings();
        if (sahBlock > 0) bs.blockSize = sahBlock;
        if (sahBins > 0) bs.binCount = sahBins;
        if (sahLeaf > 0) bs.maxLeafSize = sahLeaf;
        if (sahTraversal > 0) bs.traversalCost = sahTraversal;
        const std::vector<Aabb> bounds = [&] {
            Scene s;
            s.triangles = mesh.tris;
            return triangleBounds(s);
        }();
        const auto tBuild = Clock::now();
        Bvh bvh = buildBvh(bounds, bs);
        const double binaryMs =
            std::chrono::duration<double>(Clock::now() - tBuild).count() * 1e3;
        EmbreeScene emb(mesh), embRobust(mesh, true);
        Bvh4 bvh4 = collapseToBvh4(bvh, mesh.tris);
        DeviceBuffer<Bvh4Node> nodes(ctx, bvh4.nodes);
        DeviceBuffer<Triangle4> blocks(ctx, bvh4.blocks);
        // the eight-wide tree for --wide8 and for variants built with -DRT_BVH8
        const bool need8 = wide8 || std::any_of(variants.begin(), variants.end(), [](auto& v) {
                               return v.find("RT_BVH8") != std::string::npos;
                           });
        const auto tCollapse = Clock::now();
        Bvh8 bvh8 = need8 ? collapseToBvh8(bvh, mesh.tris) : Bvh8{};
        const double collapseMs =
            std::chrono::duration<double>(Clock::now() - tCollapse).count() * 1e3;
        DeviceBuffer<Bvh8Node> nodes8(ctx, bvh8.nodes.size());
        DeviceBuffer<Triangle4> blocks8(ctx, bvh8.blocks.size());
        if (need8) nodes8.upload(bvh8.nodes), blocks8.upload(bvh8.blocks);
        const bool need16 = std::any_of(variants.begin(), variants.end(), [](auto& v) {
            return v.find("RT_BVH16") != std::string::npos;
        });
        const auto tCollapse16 = Clock::now();
        Bvh16 bvh16 = need16 ? collapseToBvh16(bvh, mesh.tris) : Bvh16{};
        const double collapse16Ms =
            std::chrono::duration<double>(Clock::now() - tCollapse16).count() * 1e3;
        DeviceBuffer<Bvh16Node> nodes16(ctx, std::max<size_t>(1, bvh16.nodes.size()));
        DeviceBuffer<Triangle4> blocks16(ctx, std::max<size_t>(1, bvh16.blocks.size()));
        if (need16) {
            nodes16.upload(bvh16.nodes), blocks16.upload(bvh16.blocks);
            std::printf("%s: %zu sixteen-wide nodes (%.0f%% of slots used), collapse %.0f ms\n",
                        mesh.name.c_str(), bvh16.nodes.size(), 100 * usedSlots(bvh16),
                        collapse16Ms);
        }
        std::printf(
            "%s: SAH cost %.2f, %zu four-wide nodes (%.0f%% of slots used), %zu "
            "eight-wide nodes (%.0f%%), %zu blocks\n",
            mesh.name.c_str(), bvhSahCost(bvh, bs.traversalCost, bs.intersectionCost),
            bvh4.nodes.size(), 100 * usedSlots(bvh4), bvh8.nodes.size(),
            100 * usedSlots(bvh8), bvh4.blocks.size());
        if (need8)  // (one build each: a rough figure on a noisy machine)
            std::printf(
                "%s: build %.0f ms (binary SAH %.0f + eight-wide collapse %.0f), "
                "Embree's %.0f ms (rtcCommitScene)\n",
                mesh.name.c_str(), binaryMs + collapseMs, binaryMs, collapseMs,
                emb.buildMs);
        // the object, motion and sample buffers the kernels take; unused for a triangle
        // scene built without RT_HAS_QUADRICS and RT_HAS_MOTION
        DeviceBuffer<Quadric> noQuadrics(ctx, 1);
        DeviceBuffer<uint32_t> noCsg(ctx, 1), noSample(ctx, 1);
        DeviceBuffer<Triangle> noTris(ctx, 1);
        DeviceBuffer<rt_float4> noMotion(ctx, 1);
        DeviceBuffer<float> noTime(ctx, 1);
        DeviceBuffer<uint32_t> noNumerics(ctx, 1);  // archive flags: RT_HAS_PROCEDURALS only
        Rays primary = primaryRays(side, rayOrder);
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
            if (!onlyKinds.empty() &&
                std::find(onlyKinds.begin(), onlyKinds.end(), k.name) == onlyKinds.end())
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
                return p > 0 && variants[p - 1].find("RT_BVH8") != std::string::npos;
            };
            auto sixteenWide = [&](size_t p) {
                return p > 0 && variants[p - 1].find("RT_BVH16") != std::string::npos;
            };
            auto runDevice = [&](size_t p) {
                auto run = [&](auto& nodeBuf, auto& blockBuf) {
                    Kernel& kc = *kcs[p];
                    Kernel& ks = *kss[p];
                    if (k.shadow) {
                        weight.upload(ones);
                        auto t0 = Clock::now();
                        ks.launch(items(n, p > 0 ? variants[p - 1] : std::string(),
                                        "RT_SHADOW_PACKETS"),
                                  cl_uint(n), nodeBuf, blockBuf, org, dir, state, weight,
                                  noQuadrics, noCsg, noTris, noMotion, noTris, noSample,
                                  noTime, cl_uint(1), noNumerics, noNumerics, noNumerics,
                                  noNumerics, noNumerics, noNumerics);  // (opaque shadows)
                        ctx.finish();
                        return std::chrono::duration<double>(Clock::now() - t0).count();
                    }
                    auto t0 = Clock::now();
                    kc.launch(items(n, p > 0 ? variants[p - 1] : std::string(),
                                    "RT_CLOSEST_PACKETS"),
                              cl_uint(n), nodeBuf, blockBuf, org, dir, state, hits,
                              noQuadrics, noCsg, noTris, noMotion, noTris, noSample, noTime,
                              noSample);
                    ctx.finish();
                    return std::chrono::duration<double>(Clock::now() - t0).count();
                };
                if (sixteenWide(p)) return run(nodes16, blocks16);
                return eightWide(p) ? run(nodes8, blocks8) : run(nodes, blocks);
            };
            std::unique_ptr<Kernel> kc8, ks8;
            DeviceBuffer<RayHit> hits8(ctx, n);
            DeviceBuffer<RayState> state8(ctx, st, CL_MEM_READ_WRITE);
            DeviceBuffer<rt_float4> weight8(ctx, ones, CL_MEM_READ_WRITE);
            if (wide8) {
                kc8 = std::make_unique<Kernel>(ctx, program8->get(), "intersect_closest", prof);
                ks8 = std::make_unique<Kernel>(ctx, program8->get(), "intersect_shadow", prof);
            }
            auto runWide8 = [&] {
                if (k.shadow) weight8.upload(ones);
                auto t0 = Clock::now();
                if (k.shadow)
                    ks8->launch(items(n, options8, "RT_SHADOW_PACKETS"), cl_uint(n),
                                nodes8, blocks8, org, dir, state8, weight8, noQuadrics,
                                noCsg, noTris, noMotion, noTris, noSample, noTime,
                                cl_uint(1), noNumerics, noNumerics, noNumerics,
                                noNumerics, noNumerics, noNumerics);  // (opaque shadows)
                else
                    kc8->launch(items(n, options8, "RT_CLOSEST_PACKETS"), cl_uint(n), nodes8,
                                blocks8, org, dir, state8, hits8,
                                noQuadrics, noCsg, noTris, noMotion, noTris, noSample, noTime,
                                noSample);
                ctx.finish();
                return std::chrono::duration<double>(Clock::now() - t0).count();
            };
            std::vector<double> t8;
            if (wide8) runWide8();
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
            for (int r = 0; r < runs; ++r) {
                for (size_t p = 1; p < programs.size(); ++p) {
                    runDevice(p);
                    tv[p].push_back(runDevice(p));
                }
                if (wide8) {
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
            if (wide8) {
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
                const bool is16 = wide16 && p == 1;
                const std::string label = is16 ? "bvh16" : "variant " + variants[p - 1];
                std::printf("  %-38s %10.2f Mrays/s, %.3f of default, %.3f of Embree (paired %.3f)",
                            label.c_str(), n / median(tv[p]) * 1e-6, median(td) / median(tv[p]),
                            median(te) / median(tv[p]), pairedRatio(te, tv[p]));
                if (wide8) std::printf(", %.3f of bvh8", median(t8) / median(tv[p]));
                std::printf("; %.3f of Embree stream, %.3f of Embree robust\n",
                            median(tes) / median(tv[p]), median(ter) / median(tv[p]));
            }
            std::fflush(stdout);
            // The treelet path on the same rays; "agree" is bit-for-bit agreement with the
            // resident kernels (hit, t, u, v; occlusion).
            std::vector<RayHit> residentHits = hits.download();
            std::vector<rt_float4> residentShadow = weight.download();
            struct Mode {
                size_t budget, memory;  // scene memory: 0, resident
                bool eight;             // the eight-wide tree's cut
            };
            std::vector<Mode> modes;
            for (size_t b : budgets) modes.push_back({b, 0, false});
            if (streamFraction > 0)
                modes.push_back({size_t(64) << 10,
                                 std::max<size_t>(1, size_t(streamFraction * double(
                                     bvh4.nodes.size() * sizeof(Bvh4Node) +
                                     bvh4.blocks.size() * sizeof(Triangle4)))), false});
            if (treeletProgram8)
                for (size_t b : budgets) modes.push_back({b, 0, true});
            DeviceBuffer<Triangle> tris(ctx, mesh.tris);
            const TraceScene sc{noQuadrics, noCsg, tris, noMotion, tris, noSample, noTime};
            for (auto [budget, memory, eight] : modes) {
                TreeletStats ts;
                std::unique_ptr<TreeletTracer> tracerOf =
                    eight ? std::make_unique<TreeletTracer>(ctx, treeletProgram8->get(), prof,
                                                            bvh8, budget, memory, n, ts)
                          : std::make_unique<TreeletTracer>(ctx, treeletProgram.get(), prof,
                                                            bvh4, budget, memory, n, ts);
                TreeletTracer& tracer = *tracerOf;
                const std::vector<float> onesFlat(4 * n, 1.0f);  // RGB weights: 4 floats a ray
                DeviceBuffer<float> treeletWeight(ctx, onesFlat, CL_MEM_READ_WRITE);
                auto runTreelets = [&] {
                    state.upload(st);
                    treeletWeight.upload(onesFlat);
                    ctx.finish();
                    auto t0 = Clock::now();
                    if (k.shadow) tracer.shadow(cl_uint(n), org, dir, state, treeletWeight, sc, 1);
                    else tracer.closest(cl_uint(n), org, dir, state, hits, sc);
                    ctx.finish();
                    return std::chrono::duration<double>(Clock::now() - t0).count();
                };
                runTreelets();
                const TreeletStats once = ts;
                std::vector<double> tt;
                for (int r = 0; r < runs; ++r) tt.push_back(runTreelets());
                size_t agree = 0;
                if (k.shadow) {
                    auto w2 = treeletWeight.download();
                    for (size_t i = 0; i < n; ++i)
                        agree += (w2[4 * i] == 0.0f) == (residentShadow[i].x == 0.0f);
                } else {
                    auto h2 = hits.download();
                    for (size_t i = 0; i < n; ++i)
                        agree += h2[i].prim == residentHits[i].prim && h2[i].t == residentHits[i].t &&
                                 h2[i].u == residentHits[i].u && h2[i].v == residentHits[i].v;
                }
                double mt = n / median(tt) * 1e-6;
                char label[64], row[320];
                if (budget >= (size_t(1) << 30))
                    std::snprintf(label, sizeof label, "whole%s", eight ? " 8" : "");
                else std::snprintf(label, sizeof label, "%zuK%s%s", budget >> 10,
                                   memory ? " stream" : "", eight ? " 8" : "");
                std::snprintf(row, sizeof row,
                              "%-14s %-8s %-11s %8zu %7llu %10llu %8llu %10.2f %8.3f %8.3f %8.4f%%",
                              mesh.name.c_str(), k.name, label, ts.treelets,
                              (unsigned long long)once.rounds, (unsigned long long)once.pairs,
                              (unsigned long long)once.uploads, mt, mt / me, mt / md,
                              100.0 * double(agree) / double(n));
                treeletRows.push_back(row);
            }
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
