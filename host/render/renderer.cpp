// renderer.cpp: the render loop. It reads as the algorithm: analyse the scene, build the
// BVH and the specialised program, upload; then pass after pass of the sample plan. A
// pass's pixel jobs stream through the ray pool in rounds: refill the free end of the
// pool with eye rays (generate_eye, refill.h), trace (intersect_closest), sort by shader
// (none with one shader), shade, trace shadows (intersect_shadow); then close the round
// (close_round: add the shadows that reached their light, count the spawned rays),
// retire the samples with no ray left (retire_samples) and compact what the shaders
// spawned into the next round, read back at the round's one wait. When a pass's queue is
// about to run dry, the next pass is planned during a round, beside the tail still in
// flight, so the pool stays full from pass to pass (pass_planning.h: the plan and the
// film's error estimates). Between rounds it polls the stop conditions; samples still in
// flight at a stop never reach the film, so it holds only whole samples.
#include "renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <filesystem>
#include <future>
#include <memory>
#include <optional>
#include <stdexcept>

#include "cl/include/numerics_slots.h"
#include "cl/include/ray.h"
#include "device_film_sums.h"
#include "device_pixel_tests.h"
#include "device_scene.h"
#include "imager_stage.h"
#include "pass_planning.h"
#include "progress.h"
#include "ray_pool.h"
#include "refill.h"
#include "render_programs.h"
#include "render_summary.h"
#include "sample_ring.h"
#include "scene_bvh.h"
#include "shaders/shader_aovs.h"
#include "shaders/shader_set.h"
#include "stop.h"
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

// Whether the queued jobs hold at most `room` samples. Asked every round: a queue of more
// jobs than that is not walked (a job holds one sample or more).
bool queueWithin(const std::deque<PlannedJob>& pending, size_t room) {
    if (pending.size() > room) return false;
    size_t total = 0;
    for (const PlannedJob& j : pending)
        if ((total += j.count) > room) return false;
    return true;
}

// The next pass is planned once the next round takes all that is left of the queue (the
// rays left and the queued jobs fill at most this much of it): planned during that round,
// it refills the pool in the round after (stream_stats.sh at 9 samples a pixel, pool fill
// and host sync alike from 0.7 to 1.0; more passes beyond).
constexpr double kOverlapFill = 1.0;
// PoCL compiles a kernel first launched with fewer than 65536 work-items for such
// launches alone, and again at its first larger launch. retire_samples' first window is
// small and later ones pass that mark in five of the seven SPD scenes: its second compile
// cost 124-146 ms of their first renders. On PoCL it takes no more work-items a launch
// than this, and a larger window takes several launches.
constexpr size_t kPoclSmallGridItems = 65536 - 64;

const char* signalName(int sig) { return sig == 2 ? "SIGINT" : sig == 15 ? "SIGTERM" : "signal"; }

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
    std::vector<std::string> aovNames = scene.aovNames();
    for (const std::string& a : m_settings.extraAovs)
        if (std::find(aovNames.begin(), aovNames.end(), a) == aovNames.end())
            aovNames.push_back(a);
    ShadingSetup shading = ShaderSet(scene, diag).prepare(aovNames);
    // The textures those shaders may ask for: the texture search path, then the RIB's
    // folder and the current one.
    std::vector<std::string> texturePath = scene.textureSearchPath;
    {
        std::string ribDir = std::filesystem::path(scene.sourceFile).parent_path().string();
        texturePath.push_back(ribDir.empty() ? "." : ribDir);
        texturePath.push_back(".");
    }
    std::string texCache = defaultProgramCacheDir();
    TextureSet textures(texturePath,
                        (texCache.empty() ? std::filesystem::temp_directory_path().string() : texCache) +
                            "/textures",
                        diag, rib::SourceLoc{scene.sourceFile, 0});
    if (shading.textures)
        for (const std::string& name : shading.textureNames) textures.addCandidate(name);
    shading.generated["rd_textures.cl"] = textures.deviceSource();
    Features f = analyse(scene, shading);
    f.textures = shading.textures && !textures.empty();
    f.shaderAovFloats = shading.aovFloats;
    f.aovChannels = shaderAovChannels(shading.aovs);
    f.aovs = m_settings.geometricAovs || f.shaderAovFloats > 0 ||
             std::find(aovNames.begin(), aovNames.end(), "z") != aovNames.end() ||
             std::find(aovNames.begin(), aovNames.end(), "N") != aovNames.end();
    if (m_settings.seed >= 0) f.seed = uint32_t(m_settings.seed);
    if (m_settings.sobol >= 0) f.sobol = m_settings.sobol == 1;
    // Treelet-streamed traversal when a budget is set and the scene allows it.
    const size_t treeletBudget = m_settings.treeletBytes > 0 ? m_settings.treeletBytes
                                                             : size_t(scene.render.treeletBytes);
    configureTreelets(f, m_ctx, treeletBudget, st.treelets);
    if (treeletBudget > 0 && !f.treelets)
        diag.warning(rib::SourceLoc{scene.sourceFile, 0},
                     "treelet budget not used: " + st.treelets.why);
    chooseTraversal(f, m_settings.bvhWidth, m_settings.shadowPackets,
                    m_settings.closestPackets, m_ctx.info().type & CL_DEVICE_TYPE_CPU,
                    m_ctx.info().floatLanes);
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
    SamplingSettings ss;
    ss.firstPassBlock = m_settings.firstPassBlock > 0 ? m_settings.firstPassBlock
                                                      : scene.render.firstPassBlock;
    ss.pixelError = scene.render.pixelError;
    const bool openEnded = timeBudget > 0 || errorTarget > 0;
    ss.maxSamples = scene.render.maxSamples > 0 ? uint32_t(scene.render.maxSamples)
                    : openEnded                 ? 1u << 16
                                                : uint32_t(cam0.spp_x * cam0.spp_y);
    ss.minSamples =
        std::min(scene.render.minSamples > 0 ? uint32_t(scene.render.minSamples) : 2u,
                 ss.maxSamples);
    scene.camera.cropPixels(film.cropX0, film.cropX1, film.cropY0, film.cropY1);
    // (from the frame, not the pool: the image must not depend on the pool's capacity)
    ss.smallPass = m_settings.jumpSmallPasses
                       ? uint32_t(std::max<size_t>(1, film.cropPixelCount() / 64))
                       : 0;
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
    st.triangles = scene.triangles.size();
    for (const Quadric& q : scene.quadrics) {
        if (q.kind == RT_Q_CSG) ++st.csgSolids;
        else if (q.kind == RT_Q_INSTANCE) ++st.instances;
        else if (q.kind != RT_Q_MOVING_TRIANGLE) ++st.quadrics;
    }
    st.sceneBytes = nodeBytes(sceneBvh) + deviceBlocks(sceneBvh).size() * sizeof(Triangle4) +
                    scene.triangles.size() * (sizeof(Triangle) + sizeof(TriangleAttr)) +
                    scene.normals.size() * sizeof(rt_float4) +
                    scene.quadrics.size() * sizeof(Quadric) + scene.csg.size() * 4;
    st.bvhNodes = nodeCount(sceneBvh);
    st.droppedPrims = sceneBvh.droppedPrims;
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
    const size_t npix = size_t(cam.width) * size_t(cam.height);
    film.width = cam.width;
    film.exposureGain = scene.camera.exposure[0];
    film.exposureGamma = scene.camera.exposure[1];
    film.height = cam.height;
    film.pixels.assign(npix, PixelAccum{});
    // The film buffer is the film's own memory (on a CPU device; a GPU copies it at each
    // sync). The host reads it after syncToHost only, when no kernel that writes it is in
    // flight: the round's finish precedes every sync, and planning runs between passes.
    DeviceBuffer<PixelAccum> filmBuf(m_ctx, film.pixels);
    film.aovs.assign(f.aovs ? npix : 0, AovAccum{});
    DeviceBuffer<AovAccum> aovBuf(m_ctx, film.aovs);  // likewise
    film.shaderAovs = shading.aovs;
    film.shaderAovFloats = f.shaderAovFloats;
    film.shaderAovSums.assign(npix * size_t(f.shaderAovFloats), 0.0f);
    film.colours = scene.colors;
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

    Progress progress(m_settings.progress);

    auto stopNow = [&] {
        if (int sig = stopSignal()) {
            st.stopReason = signalName(sig);
            return true;
        }
        // The first round always completes, so a budget smaller than the set-up time still
        // yields an image (at the cost of overrunning it by one short round).
        if (timeBudget > 0 && st.iterations > 0 && secondsSince(t0) >= timeBudget) {
            st.stopReason = "time budget";
            return true;
        }
        return false;
    };
    // One shade kernel per shader over its run [offsets[s], + counts[s]) of `sorted`;
    // points a texture miss sends back are listed in `retry` at the same offsets.
    auto shadeRuns = [&](const std::vector<uint32_t>& counts, const std::vector<uint32_t>& offsets,
                         const DeviceBuffer<uint32_t>& sorted, DeviceBuffer<uint32_t>& retry) {
        for (cl_uint s = 0; s < shaderCount; ++s) {
            if (counts[s] == 0) continue;
            k.shade[s]->launch(
                counts[s], cl_uint(offsets[s]), cl_uint(counts[s]), sorted, rp.key,
                ds.triangles, ds.attrs, ds.normals, ds.vertexSt, ds.vertexCs, ds.vertexOs,
                ds.materials, ds.materialChannels, ds.quadrics, ds.quadricPrimvars,
                ds.quadricMotion, ds.trianglesEnd, rp.sampleTime, rp.samplePixel,
                rp.sampleIndex, rp.hitInstance, ds.params, ds.triangleParams,
                ds.pointParamValues, ds.pointParamLayout, rp.origin, rp.direction,
                rp.weight, rp.state, rp.sample, rp.hits, rp.totals, rp.nextOrigin,
                rp.nextDirection, rp.nextWeight, rp.nextState, rp.nextSample,
                rp.spawnMask, rp.slotRays, rp.shOrigin, rp.shDirection, rp.shWeight,
                rp.shState, rp.aov, rp.aovValues, rp.shAov, rp.aovw, rp.nextAovw, nl,
                numerics, textures.infoBuf, textures.pageBuf, textures.tileBuf,
                textures.requestBuf, textures.counterBuf, textures.usedBuf, retry,
                reshade.counts(), s);
        }
    };
    // The rays in the pool now, and on the spill stack. Refill tops the pool up to
    // roundCap: the whole pool, but under a time budget no more than the device traces in
    // a quarter second, and less near the budget's end (the samples in flight at a stop
    // are lost). Without one, rounds never follow the clock: the passes are planned at
    // the same rounds, and the image is the same, however fast the device runs (a first
    // round that waits on the kernels' JIT had capped the rest at a few thousand rays).
    cl_uint n = 0;
    size_t roundCap = pool;
    double raysPerSec = 0;
    size_t spillTop = 0;
    const size_t spillCapacity = RayPool::spillCapacity(pool, spawn, f.shaderShadows);
    const bool spawns = f.spawns();  // else a round leaves no ray behind
    std::vector<uint32_t> keyOffsets;
    Refill refill(ring, rp, k.generateEye, k.fitRefill, ds.cameraBuf);
    // Near the end of a time budget, a round takes only what the device traces before it.
    auto capRound = [&] {
        if (timeBudget > 0 && raysPerSec > 0)
            roundCap = std::clamp<size_t>(
                size_t(raysPerSec * std::max(0.0, timeBudget - secondsSince(t0)) * 0.9),
                std::min<size_t>(256, roundCap), roundCap);
    };
    // One round over the pool's n rays: trace, sort by shader, shade, shadows.
    auto traceRound = [&] {
        if (treelets)
            treelets->closest(n, rp.origin, rp.direction, rp.state, rp.hits, traceScene);
        else
            k.intersectClosest.launch(f.closestItems(n), n, ds.nodes, ds.blocks, rp.origin,
                                      rp.direction,
                                      rp.state, rp.hits, ds.quadrics, ds.csg, ds.triangles,
                                      ds.quadricMotion, ds.trianglesEnd, rp.sample,
                                      rp.sampleTime, rp.hitInstance);
        const cl_uint parity = cl_uint(st.iterations & 1);
        k.classify.launch(n, n, shaderCount, nl, parity, rp.hits, ds.attrs, ds.materials,
                          ds.quadrics, rp.hitInstance, rp.key, rp.keyCount, rp.keyCursor,
                          rp.spawnMask, rp.shState, rp.sample, rp.slotRays, rp.state,
                          rp.weight, rp.totals, rp.aovw, rp.aovValues);
        // One shader: no sort and no wait for the counts; its run is the whole pool in
        // order (`sorted` holds 0, 1, 2, ...) and the shade kernel skips the misses.
        if (shaderCount > 1) prof.markHostWait();
        std::vector<uint32_t> counts =
            shaderCount == 1 ? std::vector<uint32_t>{n, 0u}
                             : rp.keyCount.downloadRange(parity * (shaderCount + 1),
                                                         shaderCount + 1);
        keyOffsets.assign(counts.size(), 0);
        for (size_t s = 1; s < counts.size(); ++s)
            keyOffsets[s] = keyOffsets[s - 1] + counts[s - 1];
        if (shaderCount > 1)
            k.scatter.launch(n, n, shaderCount, parity, rp.key, rp.keyCount, rp.keyCursor,
                             rp.sorted);
        shadeRuns(counts, keyOffsets, rp.sorted, reshade.firstList());
        if (f.textures) {  // (it waits for the lists of points to shade again)
            prof.markHostWait();
            reshade.run(keyOffsets, shading.surfaceNames, shadeRuns);
        }
        if (nl > 0) {
            if (treelets)
                treelets->shadow(cl_uint(n * nl), rp.shOrigin, rp.shDirection, rp.shState,
                                 rp.shWeight, traceScene, nl,
                                 f.transparentShadows ? &shadowSurfaces : nullptr);
            else
                k.intersectShadow.launch(f.shadowItems(n, nl), cl_uint(n * nl), ds.nodes,
                                         ds.blocks, rp.shOrigin, rp.shDirection,
                                         rp.shState, rp.shWeight, ds.quadrics, ds.csg,
                                         ds.triangles, ds.quadricMotion, ds.trianglesEnd,
                                         rp.sample, rp.sampleTime, nl, numerics, ds.attrs,
                                         ds.materials, ds.materialChannels, rp.shAov,
                                         rp.slotRays);
        }
    };
    // The end of a round: add the shadow rays that reached their light and count the rays
    // the shade stage spawned (close_round), retire the jobs whose samples have no ray
    // left, both read back at one wait; then compact the spawned rays into the pool, past
    // its capacity onto the spill stack, and top the pool up from the stack (newest first,
    // as a stack keeps ray trees shallow). Pipelined (RenderSettings::pipelineRounds), the
    // compaction is queued before the wait, which waits for the round's reads alone, and
    // so are the next round's eye rays, at the pool's front, as many of the staged jobs
    // as fit_refill finds fit beside the spawned rays.
    // Retired jobs go to the film and the oldest ones free their slots; aborted jobs (a
    // ray dropped) are issued again, once.
    uint64_t nonfiniteRetired = 0;  // samples the film left out: a later pass replaces them
    uint32_t retireLaunches = 0;    // its parity picks retire_samples' progress half
    uint32_t prog[3] = {0u, 0u, 0u};  // oldest in flight, aborted, NaN/Inf
    std::vector<uint32_t> live;  // close_round's live rays per group of traced rays
    uint32_t fitted[3] = {0u, 0u, 0u};  // fit_refill's: jobs, their samples, rays spawned
    bool eyeQueued = false;  // the next round's eye rays are queued (pipelined)
    auto finishRound = [&](std::deque<PlannedJob>& pending, cl_uint traced) {
        const bool compact = spawns && traced > 0;
        const size_t groups = (traced + RT_COMPACT_GROUP - 1) / RT_COMPACT_GROUP;
        const cl_uint window = cl_uint(ring.inFlight());
        const cl_uint parity = retireLaunches & 1u, launch = retireLaunches;
        if (traced > 0 && (compact || nl > 0))
            k.closeRound.launch(traced, traced, nl, cl_uint(compact), rp.sample, rp.shWeight,
                                rp.shState, rp.totals, rp.shAov, rp.aovValues, rp.spawnMask,
                                rp.groupLive);
        if (window > 0) {
            ++retireLaunches;
            const size_t most = m_settings.retireLaunchItems > 0
                                    ? m_settings.retireLaunchItems
                                : m_ctx.info().isPocl() ? kPoclSmallGridItems
                                                        : window;
            for (size_t base = 0; base < window; base += most)
                k.retire.launch(std::min<size_t>(most, window - base),
                                cl_uint(ring.frontPosition()), window,
                                cl_uint(ring.jobCapacity()), cl_uint(ring.slotCapacity()),
                                launch, cl_uint(base), rp.jobs, rp.slotRays, rp.slotAbort,
                                rp.totals, filmBuf, rp.aov, aovBuf, rp.aovValues,
                                shaderAovBuf, rp.progress);
        }
        refill.prepare(pending, roundCap);  // while the device finishes the round
        // Pipelined, the wait is for the retire's read (none without jobs in flight).
        capRound();
        const bool pipelined = m_settings.pipelineRounds && window > 0;
        const bool refilled = pipelined && refill.fit(compact ? groups : 0, spillTop, roundCap);
        if (refilled) {
            rp.refillFit.downloadRangeTo(0, 3, fitted, /*blocking=*/false);
        } else if (compact) {
            live.resize(groups);
            rp.groupLive.downloadRangeTo(0, groups, live.data(), /*blocking=*/false);
        }
        cl_event readsDone = nullptr;
        if (window > 0)
            rp.progress.downloadRangeTo(3 * parity, 3, prog, /*blocking=*/false, &readsDone);
        auto compactBehind = [&](cl_uint base) {
            k.compactScatter.launch(
                traced, traced, base, rp.refillFit, cl_uint(pool), cl_uint(spillTop),
                cl_uint(spillCapacity), rp.groupLive, rp.spawnMask, rp.nextOrigin,
                rp.nextDirection, rp.nextWeight, rp.nextState, rp.nextSample, rp.origin,
                rp.direction, rp.weight, rp.state, rp.sample, rp.spillOrigin,
                rp.spillDirection, rp.spillWeight, rp.spillState, rp.spillSample,
                rp.nextAovw, rp.aovw, rp.spillAovw, rp.slotRays, rp.slotAbort, nl,
                rp.shOrigin, rp.shDirection, rp.shWeight, rp.shState, rp.shAov);
        };
        if (refilled) refill.commitFitted(pending);  // eye rays at the pool's front
        if (pipelined && compact) compactBehind(refilled ? ~0u : 0u);  // spawned rays behind
        prof.markHostWait();
        if (pipelined) m_ctx.wait(readsDone);
        else {
            if (readsDone) clReleaseEvent(readsDone);
            m_ctx.finish();
        }
        size_t added = 0, total = 0;
        if (refilled) {
            refill.bookFitted(pending, fitted[0]);
            added = fitted[1], total = fitted[2];
            st.eyeRays += added;
            // (else the next round's start commits after all; and it adds what the slot
            // ring held back before the retire freed slots)
            eyeQueued = added > 0 && !refill.fittedRingBound();
        } else if (compact) {
            for (size_t g = 0; g < groups; ++g) total += live[g];
            if (!pipelined && total > 0) compactBehind(0);
        }
        const size_t held = added + total;  // (compact_scatter spills past the pool)
        n = cl_uint(std::min(held, pool));
        if (compact) {
            if (held > pool) {
                const size_t spilled = std::min(held - pool, spillCapacity - spillTop);
                st.overflowRays += held - pool - spilled;  // dropped: the sample goes again
                spillTop += spilled;
                st.spilledRays += spilled;
            } else if (spillTop > 0) {
                const size_t take = std::min(pool - n, spillTop);
                const size_t from = spillTop - take;
                rp.spillOrigin.copyTo(rp.origin, from, n, take);
                rp.spillDirection.copyTo(rp.direction, from, n, take);
                rp.spillWeight.copyTo(rp.weight, from * rp.weightFloats, n * rp.weightFloats,
                                      take * rp.weightFloats);
                rp.spillState.copyTo(rp.state, from, n, take);
                rp.spillSample.copyTo(rp.sample, from, n, take);
                if (rp.rayAovFloats > 0)
                    rp.spillAovw.copyTo(rp.aovw, from * rp.rayAovFloats,
                                        n * rp.rayAovFloats, take * rp.rayAovFloats);
                spillTop = from;
                n += cl_uint(take);
            }
        }
        if (window == 0) return;
        nonfiniteRetired += prog[2];
        if (prog[1] > 0) {
            std::vector<PixelJob> all = rp.jobs.download();
            for (size_t j = window; j-- > 0;) {
                PixelJob& r = all[(ring.frontPosition() + j) % ring.jobCapacity()];
                if ((r.state & RT_JOB_STATE_MASK) != RT_JOB_ABORTED) continue;
                r.state = RT_JOB_RETIRED;
                PlannedJob again = ring.at(j);
                again.lastTry = true;
                pending.push_front(again);
                st.reissuedSamples += again.count;
            }
            rp.jobs.upload(all);
            refill.invalidate();  // the front of `pending` changed
        }
        const size_t retired = std::min<size_t>(prog[0], window);
        st.retiredSamples += ring.samplesInFront(retired);
        ring.popFront(retired);
    };

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
    // Passes overlap (RenderSettings::overlapPasses) when a pass can follow the first.
    const bool overlapPasses =
        m_settings.overlapPasses && (ss.maxSamples > ss.minSamples || errorTarget > 0);
    auto planPass = [&](const std::deque<PlannedJob>& pending) {
        std::deque<PlannedJob> jobs = planning.planPass(pending);
        refill.invalidate();  // a new queue
        return jobs;
    };
    // The pass's jobs stream through the pool: refill, trace, compact, retire, until every
    // job has retired (the caller has staged its first refill or invalidated the last
    // pass's). With overlapPasses, once the next round takes all that is left (the rays
    // and the queued jobs: kOverlapFill), the next pass is planned from the film as the
    // round left it, during the next round's kernels (none of which writes the film
    // before that round's retire), and streams on beside the tail: its eye rays keep the
    // pool full. Returns false when a stop ends it early.
    auto runPass = [&](std::deque<PlannedJob> pending) {
        bool overlap = overlapPasses, planDue = false;
        while (!pending.empty() || ring.inFlight() > 0) {
            if (stopNow()) return false;
            if (!eyeQueued) {
                capRound();
                const cl_uint added = refill.commit(pending, n, n, roundCap);
                n += added;
                st.eyeRays += added;
            }
            eyeQueued = false;
            if (n == 0 && spillTop == 0 && ring.inFlight() == 0)
                throw std::runtime_error("internal error: a pixel job larger than the ray pool");
            const auto tRound = Clock::now();
            double planSec = 0;  // of the round's time: planning the next pass
            const cl_uint traced = n;
            if (n > 0) {
                traceRound();
                if (st.poolFillSeries.empty() ||
                    secondsSince(t0) - st.poolFillSeries.back().seconds >= 0.05)
                    st.poolFillSeries.push_back(
                        {secondsSince(t0), double(n) / double(pool)});
            }
            refill.book(pending);
            if (planDue) {
                planDue = false;
                const auto tPlan = Clock::now();
                std::deque<PlannedJob> next = planPass(pending);
                planSec = secondsSince(tPlan);
                // the device may have run out of queued kernels meanwhile: the host's time
                prof.markHostWait();
                // nothing to add beside the tail: drain it, then plan with every pixel known
                overlap = !next.empty();
                st.overlappedPasses += overlap;
                if (pending.empty()) pending = std::move(next);
                else pending.insert(pending.end(), next.begin(), next.end());
            }
            const size_t inFlightBefore = ring.inFlight();
            finishRound(pending, traced);  // its read waits for the round: time it here
            // No ray anywhere yet a job still in flight would loop for ever: a sample's
            // count of rays went wrong. Never hang: stop with a clear error.
            if (traced == 0 && spillTop == 0 && ring.inFlight() == inFlightBefore &&
                inFlightBefore > 0)
                throw std::runtime_error("internal error: samples in flight with no ray left");
            // (a round of a few rays is its fixed costs: no measure of the rate)
            if (const double dt = secondsSince(tRound) - planSec;
                dt > 0 && (traced >= pool / 8 || (traced > 0 && raysPerSec == 0))) {
                raysPerSec = double(traced) / dt;
                if (timeBudget > 0)
                    roundCap = std::clamp<size_t>(size_t(raysPerSec * 0.25),
                                                  std::min<size_t>(1024, pool), pool);
            }
            ++st.iterations;
            if (f.procedurals) {  // a ray reached an archive's bound: load it first
                prof.markHostWait();
                std::vector<uint32_t> flags = numerics.download();
                for (size_t a = 0; a < scene.procedurals.size(); ++a)
                    if (flags[kProceduralFlags + a])
                        st.proceduralsReached.push_back(scene.procedurals[a].key);
                if (!st.proceduralsReached.empty()) {
                    st.stopReason = "archives to load";
                    return false;
                }
            }
            planning.sampleError(false);
            double fraction =
                timeBudget > 0 ? secondsSince(t0) / timeBudget
                : errorTarget > 0 && st.estimatedError > 0
                    ? std::min(1.0, std::log(1.0 / st.estimatedError) /
                                        std::log(1.0 / errorTarget))
                    : double(st.retiredSamples) / double(film.cropPixelCount() * ss.maxSamples);
            progress.update(fraction, secondsSince(t0), st.eyeRays, st.estimatedError);
            const size_t fill = size_t(kOverlapFill * double(roundCap));
            if (overlap && (ring.inFlight() > 0 || !pending.empty()) && spillTop == 0 &&
                n <= fill && queueWithin(pending, fill - n)) {
                planDue = !planning.readFilm();  // the error target met: drain, then stop
                overlap = planDue;
            }
        }
        return true;
    };

    prof.markHostWait();  // the set-up: the device had nothing to do before the loop
    for (;;) {
        std::deque<PlannedJob> jobs;
        if (first) {
            jobs = std::move(first->jobs);
            refill.adopt(std::move(first->refill));
            st.planMs += firstPlanMs;
            first.reset();
        } else {
            jobs = planPass({});
        }
        if (jobs.empty()) {
            st.stopReason = "quality";
            break;
        }
        if (!runPass(std::move(jobs))) {
            st.abortedSamples = ring.samplesInFlight();  // in flight: never reach the film
            break;
        }
        if (planner->firstPassIsFinal() && nonfiniteRetired == 0 && errorTarget <= 0) {
            st.stopReason = "quality";  // every pixel has all its samples: nothing to plan
            break;
        }
        if (planning.readFilm()) {
            st.stopReason = "error target";
            break;
        }
    }
    progress.finish();
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
