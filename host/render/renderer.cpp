// renderer.cpp: a frame, as DESIGN.md section 3 lays it out: analyse the scene (dice
// what is truly displaced, compile its shaders, pick the features its kernels need),
// build the BVH and the specialised programs, upload; then the passes of the sample plan
// stream through the ray pool in rounds (render_loop.h), and the frame's figures are
// gathered for --stats. The first pass is planned, and the programs built, on other
// threads while the BVH is built.
#include "renderer.h"

#include <algorithm>
#include <chrono>
#include <deque>
#include <filesystem>
#include <future>
#include <memory>
#include <optional>

#include "cl/include/numerics_slots.h"
#include "cl/include/ray.h"
#include "device_film_sums.h"
#include "device_pixel_tests.h"
#include "device_scene.h"
#include "imager_stage.h"
#include "pass_planning.h"
#include "ray_pool.h"
#include "refill.h"
#include "render_loop.h"
#include "render_programs.h"
#include "render_summary.h"
#include "sample_ring.h"
#include "scene_bvh.h"
#include "shaders/shader_aovs.h"
#include "shaders/shader_set.h"
#include "texture_reshade.h"
#include "true_displacement.h"

namespace rd {

// the first archive flag after the counters
constexpr size_t kProceduralFlags = RT_NUM_PROCEDURAL_BASE;
namespace {

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

// The scene's AOVs and those the command line adds.
std::vector<std::string> frameAovNames(const Scene& scene,
                                       const RenderSettings& settings) {
    std::vector<std::string> names = scene.aovNames();
    for (const std::string& a : settings.extraAovs)
        if (std::find(names.begin(), names.end(), a) == names.end()) names.push_back(a);
    return names;
}

// Where textures are looked for: the texture search path, then the RIB's folder and the
// current one.
std::vector<std::string> texturePathOf(const Scene& scene) {
    std::vector<std::string> path = scene.textureSearchPath;
    std::string ribDir = std::filesystem::path(scene.sourceFile).parent_path().string();
    path.push_back(ribDir.empty() ? "." : ribDir);
    path.push_back(".");
    return path;
}

std::string textureCacheDir() {
    const std::string cache = defaultProgramCacheDir();
    return (cache.empty() ? std::filesystem::temp_directory_path().string() : cache) +
           "/textures";
}

// What the scene's kernels need (features.h), with the command line's choices: the
// features the shaders' AOVs and textures ask for, the treelets, the traversal.
Features frameFeatures(const Scene& scene, const ShadingSetup& shading,
                       const TextureSet& textures,
                       const std::vector<std::string>& aovNames,
                       const RenderSettings& settings, const ClContext& ctx,
                       size_t treeletBudget, RenderStats& st, rib::Diagnostics& diag) {
    Features f = analyse(scene, shading);
    f.textures = shading.textures && !textures.empty();
    f.shaderAovFloats = shading.aovFloats;
    f.aovChannels = shaderAovChannels(shading.aovs);
    f.aovs = settings.geometricAovs || f.shaderAovFloats > 0 ||
             std::find(aovNames.begin(), aovNames.end(), "z") != aovNames.end() ||
             std::find(aovNames.begin(), aovNames.end(), "N") != aovNames.end();
    if (settings.seed >= 0) f.seed = uint32_t(settings.seed);
    if (settings.sobol >= 0) f.sobol = settings.sobol == 1;
    // Treelet-streamed traversal when a budget is set and the scene allows it.
    configureTreelets(f, ctx, treeletBudget, st.treelets);
    if (treeletBudget > 0 && !f.treelets)
        diag.warning(rib::SourceLoc{scene.sourceFile, 0},
                     "treelet budget not used: " + st.treelets.why);
    chooseTraversal(f, settings.bvhWidth, settings.shadowPackets, settings.closestPackets,
                    ctx.info().type & CL_DEVICE_TYPE_CPU, ctx.info().floatLanes);
    return f;
}

// The sample plan's settings: the scene's, the command line's first-pass block, and an
// open end when a time budget or an error target decides when to stop.
SamplingSettings frameSampling(const Scene& scene, const RenderSettings& settings,
                               const Camera& cam, const Film& film, bool openEnded) {
    SamplingSettings ss;
    ss.firstPassBlock = settings.firstPassBlock > 0 ? settings.firstPassBlock
                                                    : scene.render.firstPassBlock;
    ss.pixelError = scene.render.pixelError;
    ss.maxSamples = scene.render.maxSamples > 0 ? uint32_t(scene.render.maxSamples)
                    : openEnded                 ? 1u << 16
                                                : uint32_t(cam.spp_x * cam.spp_y);
    ss.minSamples =
        std::min(scene.render.minSamples > 0 ? uint32_t(scene.render.minSamples) : 2u,
                 ss.maxSamples);
    // (from the frame, not the pool: the image must not depend on the pool's capacity)
    ss.smallPass = settings.jumpSmallPasses
                       ? uint32_t(std::max<size_t>(1, film.cropPixelCount() / 64))
                       : 0;
    return ss;
}

// --stats' counts of the scene's surfaces and the bytes of its device arrays.
void countScene(const Scene& scene, const SceneBvh& bvh, RenderStats& st) {
    st.triangles = scene.triangles.size();
    for (const Quadric& q : scene.quadrics) {
        if (q.kind == RT_Q_CSG)
            ++st.csgSolids;
        else if (q.kind == RT_Q_INSTANCE)
            ++st.instances;
        else if (q.kind != RT_Q_MOVING_TRIANGLE)
            ++st.quadrics;
    }
    st.sceneBytes = nodeBytes(bvh) + deviceBlocks(bvh).size() * sizeof(Triangle4) +
                    scene.triangles.size() * (sizeof(Triangle) + sizeof(TriangleAttr)) +
                    scene.normals.size() * sizeof(rt_float4) +
                    scene.quadrics.size() * sizeof(Quadric) + scene.csg.size() * 4;
    st.bvhNodes = nodeCount(bvh);
    st.droppedPrims = bvh.droppedPrims;
}

// The film's pixels and AOVs, zeroed, for the camera's image.
void clearFilm(Film& film, const Camera& cam, const Scene& scene,
               const ShadingSetup& shading, const Features& f) {
    const size_t npix = size_t(cam.width) * size_t(cam.height);
    film.width = cam.width;
    film.height = cam.height;
    film.exposureGain = scene.camera.exposure[0];
    film.exposureGamma = scene.camera.exposure[1];
    film.pixels.assign(npix, PixelAccum{});
    film.aovs.assign(f.aovs ? npix : 0, AovAccum{});
    film.shaderAovs = shading.aovs;
    film.shaderAovFloats = f.shaderAovFloats;
    film.shaderAovSums.assign(npix * size_t(f.shaderAovFloats), 0.0f);
    film.colours = scene.colors;
}

}  // namespace

Renderer::Renderer(const ClContext& ctx, const RenderSettings& settings)
    : m_ctx(ctx), m_settings(settings) {}

RenderStats Renderer::render(const Scene& input, Film& film, rib::Diagnostics& diag) {
    const auto t0 = Clock::now();
    RenderStats st;
    // Truly displaced surfaces are diced first (dice_displaced.h): the render is of a
    // copy of the scene with their micropolygons, moved once the shading program is
    // built.
    std::optional<Scene> dicedScene;
    DicedSurfaces diced;
    const bool dicing = hasTrueDisplacement(input);
    const DicingView dicingView =
        dicing ? dicingViewOf(input.deviceCamera()) : DicingView{};
    if (dicing) {
        dicedScene.emplace(input);
        diced = diceDisplacedSurfaces(*dicedScene, dicingView,
                                      input.render.dicedTriangles > 0
                                          ? size_t(input.render.dicedTriangles)
                                          : kMaxDicedTriangles);
        reportDicing(diced, input, diag);
    }
    const Scene& scene = dicedScene ? *dicedScene : input;
    st.device = m_ctx.name();
    st.platform = m_ctx.info().platformName;
    st.threadsPinned = m_ctx.info().isPocl() && poclThreadsPinned();
    // The scene's RSL shaders, compiled and bound: they decide lights, trace and more.
    const std::vector<std::string> aovNames = frameAovNames(scene, m_settings);
    ShadingSetup shading = ShaderSet(scene, diag).prepare(aovNames);
    // The textures those shaders may ask for.
    TextureSet textures(texturePathOf(scene), textureCacheDir(), diag,
                        rib::SourceLoc{scene.sourceFile, 0});
    if (shading.textures)
        for (const std::string& name : shading.textureNames) textures.addCandidate(name);
    shading.generated["rd_textures.cl"] = textures.deviceSource();
    const size_t treeletBudget = m_settings.treeletBytes > 0 ? m_settings.treeletBytes
                                                             : size_t(scene.render.treeletBytes);
    const Features f = frameFeatures(scene, shading, textures, aovNames, m_settings,
                                     m_ctx, treeletBudget, st, diag);
    st.features = f;

    // Budgets: the command line wins over Option "render".
    const double timeBudget = m_settings.timeBudget > 0 ? m_settings.timeBudget
                                                        : scene.render.time;
    const double errorTarget = m_settings.errorTarget > 0 ? m_settings.errorTarget
                                                          : scene.render.error;

    const uint32_t nl = f.shadowSlots();
    const size_t spawn = size_t(f.spawnSlots());
    const cl_uint shaderCount = cl_uint(shading.shadeKernels.size());
    // The pool (RayPool::capacityFor); the sample slots kSlotsPerRay times it, pixel jobs
    // at most a quarter of it so several pixels share a round.
    const size_t weightFloats = RayPool::weightFloatsOf(f.colors.n);
    const size_t aovFloats = size_t(f.shaderAovFloats);
    const size_t rayAovFloats = size_t(f.rayAovFloats());
    const size_t pool = RayPool::capacityFor(m_settings.poolCapacity, m_ctx.info(), spawn,
                                             nl, weightFloats, aovFloats, rayAovFloats,
                                             f.shaderShadows);
    st.poolCapacity = pool;
    st.poolBytesPerRay =
        RayPool::bytesPerRay(spawn, nl, weightFloats, aovFloats, rayAovFloats, f.shaderShadows);
    SampleRing ring(RayPool::kSlotsPerRay * pool);
    const uint32_t maxJob = uint32_t(std::max<size_t>(1, pool / 4));
    // Sampling: the first pass needs no film, so it is planned on another thread while
    // the BVH and the program are built (on a small frame it costs as much as a round).
    const Camera cam0 = scene.deviceCamera();
    scene.camera.cropPixels(film.cropX0, film.cropX1, film.cropY0, film.cropY1);
    const SamplingSettings ss =
        frameSampling(scene, m_settings, cam0, film, timeBudget > 0 || errorTarget > 0);
    std::optional<SamplePlanner> planner;
    double firstPlanMs = 0;
    // (and its first refill staged: the ring is empty and the round cap the pool until then)
    // (and the memory the device's tests of every pixel answer in: devicePixelTests)
    const bool testsOnDevice =
        m_settings.devicePixelTests && m_ctx.info().fp64 &&
        size_t(cam0.width) * size_t(cam0.height) >= m_settings.devicePixelTestsFrom;
    struct FirstPass {
        std::deque<PlannedJob> jobs;
        RefillStage refill;
        std::optional<PixelTestMemory> testMemory;
    };
    std::future<FirstPass> firstPass = std::async(std::launch::async, [&] {
        const auto tp = Clock::now();
        planner.emplace(cam0.width, cam0.height, film.cropX0, film.cropX1, film.cropY0,
                        film.cropY1, ss);
        // (a first pass without blocks reads the film: all zeros yet)
        const FilmPixels none(
            ss.firstPassBlock > 1 ? 0 : size_t(cam0.width) * size_t(cam0.height));
        std::deque<PlannedJob> jobs = planJobs(
            planner->nextPass(none, errorTarget > 0 ? float(errorTarget) : ss.pixelError),
            maxJob, size_t(cam0.width) * size_t(cam0.height));
        RefillStage stage;
        stageRefill(ring, jobs, pool, stage);
        std::optional<PixelTestMemory> testMemory;
        if (testsOnDevice)
            testMemory.emplace(*planner, cam0.width, cam0.height);
        firstPlanMs = secondsSince(tp) * 1e3;
        return FirstPass{std::move(jobs), std::move(stage), std::move(testMemory)};
    });

    // Scene -> BVH -> specialised programs (trace, shading) -> device arrays. The programs
    // build on another thread while the BVH is built: neither needs the other (a cold
    // build is a second or more of the compiler, a warm one 40-60 ms on PoCL).
    std::future<RenderPrograms> programBuild = std::async(
        std::launch::async, [&] { return RenderPrograms(m_ctx, shading, buildOptions(f)); });
    // Textures: the device tile cache (Option "limits" "texturememory" or the command
    // line; else every tile when they fit in 256 MiB).
    size_t cacheTiles = m_settings.textureCacheTiles;
    if (cacheTiles == 0 && scene.render.textureMemoryKB > 0)
        cacheTiles = size_t(scene.render.textureMemoryKB) * 1024 /
                     (sizeof(rt_float4) * RT_TEX_TILE_TEXELS);
    textures.createDevice(m_ctx, f.textures ? cacheTiles : 1);
    Profiler prof(m_ctx);
    if (m_settings.timeline) prof.keepTimeline();
    // Displacement moves the diced surfaces before their tree is built: it waits for
    // the program.
    std::optional<RenderPrograms> builtEarly;
    if (dicedScene && !diced.vertexCorner.empty()) {
        builtEarly.emplace(programBuild.get());
        const auto td = Clock::now();
        const DisplacementReport dr = displaceDicedSurfaces(
            m_ctx, builtEarly->shade->get(), prof, *dicedScene, diced, f, shading,
            textures, dicingView, dicingView.perspective ? 0.0f : dicingView.pixelWidth);
        st.displacedVertices = dr.vertices;
        st.displaceMs = secondsSince(td) * 1e3;
        reportDisplacement(dr, scene, diag);
    }
    st.dicedTriangles = diced.cornerVertex.size() / 3;
    auto tb = Clock::now();
    SceneBvh sceneBvh = buildSceneBvh(scene, f.bvhWidth);
    st.bvhBuildMs = secondsSince(tb) * 1e3;
    countScene(scene, sceneBvh, st);
    // The device's arrays and the ray pool while the programs build (a warm build of the
    // two is 60-70 ms on PoCL, most of it its preprocessor)
    DeviceScene ds(m_ctx, scene, sceneBvh, f, shading);
    RayPool rp(m_ctx, pool, spawn, nl, ring.slotCapacity(), f.aovs, f.motion, f.instances,
               shaderCount + 1, weightFloats, aovFloats, rayAovFloats, f.shaderShadows);
    if (shaderCount == 1) {  // the one shader's run: every ray in pool order
        std::vector<uint32_t> order(pool);
        for (size_t i = 0; i < pool; ++i) order[i] = uint32_t(i);
        rp.sorted.upload(order);
    }
    const RenderPrograms programs =
        builtEarly ? std::move(*builtEarly) : programBuild.get();
    st.program = programs.info();
    st.traceProgram = programs.trace->info();
    st.shadeProgram = programs.shade->info();
    RenderKernels k(m_ctx, programs.trace->get(), programs.shade->get(), prof,
                    shading.shadeKernels);
    if (f.shadowPackets) k.intersectShadow.setLanesPerItem(RT_PACKET_RAYS);
    if (f.closestPackets) k.intersectClosest.setLanesPerItem(RT_PACKET_RAYS);
    if (!shading.prepares.empty()) {  // the shaders' uniform work, once per instance
        Kernel prepare(m_ctx, programs.shade->get(), "rd_prepare_uniforms", prof);
        prepare.launch(shading.prepares.size(), cl_uint(shading.prepares.size()), ds.params);
        prepare.collectActive();
    }
    const Camera& cam = ds.camera;
    std::unique_ptr<TreeletTracer> treelets;  // instead of the two intersect launches
    if (f.treelets) {  // cut from the tree the program walks
        const size_t sceneMemory = m_settings.sceneMemoryBytes > 0
                                       ? m_settings.sceneMemoryBytes
                                       : size_t(scene.render.sceneMemoryKB) << 10;
        treelets = withTree(sceneBvh, [&](const auto& tree) {
            return std::make_unique<TreeletTracer>(m_ctx, programs.trace->get(), prof, tree,
                                                   treeletBudget, sceneMemory, pool, st.treelets);
        });
    }
    const TraceScene traceScene{ds.quadrics,      ds.csg,    ds.triangles, ds.quadricMotion,
                                ds.trianglesEnd, rp.sample, rp.sampleTime};
    const ShadowSurfaces shadowSurfaces{ds.attrs,  ds.materials,          ds.materialChannels,
                                        rp.shAov,  f.maxTransparentDepth, rp.slotRays};
    // The lists of points to shade again once the tiles they missed are there.
    TextureReshade reshade(m_ctx, textures, pool, shaderCount, f.textures);
    clearFilm(film, cam, scene, shading, f);
    // The film buffer is the film's own memory (on a CPU device; a GPU copies it at each
    // sync). The host reads it after syncToHost only, when no kernel that writes it is in
    // flight: the round's finish precedes every sync, and planning runs between passes.
    DeviceBuffer<PixelAccum> filmBuf(m_ctx, film.pixels);
    DeviceBuffer<AovAccum> aovBuf(m_ctx, film.aovs);              // likewise
    DeviceBuffer<float> shaderAovBuf(m_ctx, film.shaderAovSums);  // likewise
    // numerics.clh RT_NUM_* counters, then a flag per archive not loaded yet
    DeviceBuffer<uint32_t> numerics(m_ctx, kProceduralFlags + scene.procedurals.size());
    numerics.fillZero();
    std::optional<FirstPass> first = firstPass.get();
    std::optional<DevicePixelTests> pixelTests;  // where the device has double precision
    if (first->testMemory) {
        pixelTests.emplace(m_ctx, programs.trace->get(), prof, filmBuf, cam.width, cam.height,
                           *planner, std::move(*first->testMemory));
        planner->setTester(&*pixelTests);
    }
    std::optional<DeviceFilmSums> filmSums;  // the end of frame's, likewise
    if (testsOnDevice) filmSums.emplace(m_ctx, programs.trace->get(), prof, filmBuf, film);
    st.sceneSetupMs = secondsSince(t0) * 1e3;

    PassTargets targets;
    targets.pixelError = ss.pixelError;
    targets.errorTarget = errorTarget;
    targets.timeBudget = timeBudget;
    targets.sobol = f.sobol;
    targets.errorSeriesSec = m_settings.errorSeriesSec;
    targets.maxJob = maxJob;
    PassPlanning planning(targets, film, filmBuf, planner, ring, prof, st, t0, [&] {
        return uint64_t(k.intersectClosest.peekActive() + k.intersectShadow.peekActive() +
                        (treelets ? treelets->peekRays() : 0));
    });
    const FrameDevice device{
        m_ctx, scene,          f,          shading,        ds,           rp,
        k,     treelets.get(), traceScene, shadowSurfaces, textures,     reshade,
        prof,  ring,           filmBuf,    aovBuf,         shaderAovBuf, numerics};
    FrameLimits limits;
    limits.pool = pool;
    limits.timeBudget = timeBudget;
    limits.errorTarget = errorTarget;
    // Passes overlap when a pass can follow the first.
    limits.overlapPasses =
        m_settings.overlapPasses && (ss.maxSamples > ss.minSamples || errorTarget > 0);
    limits.plannedSamples = double(film.cropPixelCount() * ss.maxSamples);
    RenderLoop loop(device, m_settings, limits, planning, *planner, st, t0);
    loop.run(std::move(first->jobs), std::move(first->refill), firstPlanMs);
    first.reset();
    if (shading.imager) {  // the Imager shader on the finished image (also a stopped one)
        filmBuf.syncToHost();
        film.imaged = applyImager(m_ctx, programs.shade->get(), prof, film, ds.params);
    } else {  // the film's sync overlaps the profiler's reads; collectActive waits for it
        filmBuf.syncToHost(/*blocking=*/false);
    }
    if (filmSums) filmSums->launch();
    aovBuf.syncToHost(/*blocking=*/false);
    shaderAovBuf.syncToHost(/*blocking=*/false);
    std::vector<uint32_t> num, texCounts;
    numerics.downloadInto(num, /*blocking=*/false);
    if (f.textures) textures.counterBuf.downloadInto(texCounts, /*blocking=*/false);
    prof.collect();
    std::vector<Kernel*> kernels = k.all();
    if (pixelTests) {
        for (Kernel* t : pixelTests->kernels()) kernels.push_back(t);
    }
    if (filmSums) kernels.push_back(&filmSums->kernel());
    Kernel::collectActive(kernels);
    if (treelets) treelets->collectActive();
    m_ctx.finish();  // the copies above
    st.kernels = prof.stats();
    st.timeline = prof.timeline();
    if (f.textures) {
        textures.stats().lookups = texCounts[1];
        textures.stats().missedLookups = texCounts[2];
        st.textures = textures.stats();
    }
    summariseRays(st, num, f.maxTransparentDepth, diag, rib::SourceLoc{scene.sourceFile, 0});
    const std::optional<FilmSummary> filmSummary =
        filmSums ? std::optional<FilmSummary>(filmSums->summary()) : std::nullopt;
    summariseFilm(st, film, f.sobol, ss.maxSamples >= 2, filmSummary ? &*filmSummary : nullptr);
    st.passes = planner->passes();
    st.elapsedSec = secondsSince(t0);
    summariseOccupancy(st, treelets != nullptr, prof.launchGapsMs());
    st.errorVsTime.push_back({st.elapsedSec, st.totalRays(), st.estimatedError});
    return st;
}

}  // namespace rd
