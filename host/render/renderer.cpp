// renderer.cpp: a frame, as DESIGN.md section 3 lays it out: analyse the scene (dice
// what is truly displaced, compile its shaders, pick the features its kernels need),
// build the BVH and the specialised programs, upload; then the passes of the sample plan
// stream through the ray pool in rounds (render_loop.h), and the frame's figures are
// gathered for --stats (frame_finish.h). The first pass is planned, and the programs
// built, on other threads while the BVH is built.
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
#include "frame_finish.h"
#include "pass_planning.h"
#include "ray_pool.h"
#include "refill.h"
#include "render_loop.h"
#include "render_programs.h"
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

// The scene a frame renders: the input, or a copy of it whose truly displaced surfaces
// are diced (dice_displaced.h), their micropolygons moved once the shading program is
// built.
struct FrameScene {
    std::optional<Scene> diced;
    DicedSurfaces surfaces;
    DicingView view;
};

FrameScene diceTrueDisplacement(const Scene& input, rib::Diagnostics& diag) {
    FrameScene fs;
    if (!hasTrueDisplacement(input)) return fs;
    fs.view = dicingViewOf(input.deviceCamera());
    fs.diced.emplace(input);
    fs.surfaces = diceDisplacedSurfaces(*fs.diced, fs.view,
                                        input.render.dicedTriangles > 0
                                            ? size_t(input.render.dicedTriangles)
                                            : kMaxDicedTriangles);
    reportDicing(fs.surfaces, input, diag);
    return fs;
}

// When the frame stops besides its samples: the command line wins over Option "render".
struct FrameBudgets {
    double time = 0;   // seconds; 0: none
    double error = 0;  // the film's relative error; 0: none
};

FrameBudgets frameBudgets(const RenderSettings& settings, const Scene& scene) {
    return {settings.timeBudget > 0 ? settings.timeBudget : scene.render.time,
            settings.errorTarget > 0 ? settings.errorTarget : scene.render.error};
}

// The ray pool's shape (RayPool::capacityFor): what each ray carries, the rays a round.
struct PoolShape {
    uint32_t shadowSlots = 0;  // shadow rays a shaded ray may send
    size_t spawn = 0;          // rays a shaded ray may spawn
    cl_uint shaderCount = 0;   // shade kernels: the sort's keys, less the misses'
    size_t weightFloats = 0, aovFloats = 0, rayAovFloats = 0;
    bool shaderShadows = false;
    size_t capacity = 0;
    size_t bytesPerRay() const {
        return RayPool::bytesPerRay(spawn, shadowSlots, weightFloats, aovFloats,
                                    rayAovFloats, shaderShadows);
    }
    // Pixel jobs at most a quarter of the pool, so that several pixels share a round.
    uint32_t maxJob() const { return uint32_t(std::max<size_t>(1, capacity / 4)); }
};

PoolShape poolShapeOf(const Features& f, const ShadingSetup& shading,
                      const ClContext& ctx, size_t wanted) {
    PoolShape p;
    p.shadowSlots = f.shadowSlots();
    p.spawn = size_t(f.spawnSlots());
    p.shaderCount = cl_uint(shading.shadeKernels.size());
    p.weightFloats = RayPool::weightFloatsOf(f.colors.n);
    p.aovFloats = size_t(f.shaderAovFloats);
    p.rayAovFloats = size_t(f.rayAovFloats());
    p.shaderShadows = f.shaderShadows;
    p.capacity =
        RayPool::capacityFor(wanted, ctx.info(), p.spawn, p.shadowSlots, p.weightFloats,
                             p.aovFloats, p.rayAovFloats, p.shaderShadows);
    return p;
}

// The first pass, planned (with its first refill staged: the ring is empty and the round
// cap the pool until then) on another thread while the BVH and the programs are built,
// as it needs no film (on a small frame it costs as much as a round); with the memory
// the device's tests of every pixel answer in (devicePixelTests).
struct FirstPass {
    std::deque<PlannedJob> jobs;
    RefillStage refill;
    std::optional<PixelTestMemory> testMemory;
    double planMs = 0;
};

FirstPass planFirstPass(std::optional<SamplePlanner>& planner, const Camera& cam,
                        const Film& film, const SamplingSettings& ss, double errorTarget,
                        const PoolShape& pool, SampleRing& ring, bool testsOnDevice) {
    const auto tp = Clock::now();
    const size_t pixels = size_t(cam.width) * size_t(cam.height);
    planner.emplace(cam.width, cam.height, film.cropX0, film.cropX1, film.cropY0,
                    film.cropY1, ss);
    // (a first pass without blocks reads the film: all zeros yet)
    const FilmPixels none(ss.firstPassBlock > 1 ? 0 : pixels);
    FirstPass first;
    first.jobs = planJobs(
        planner->nextPass(none, errorTarget > 0 ? float(errorTarget) : ss.pixelError),
        pool.maxJob(), pixels);
    stageRefill(ring, first.jobs, pool.capacity, first.refill);
    if (testsOnDevice) first.testMemory.emplace(*planner, cam.width, cam.height);
    first.planMs = secondsSince(tp) * 1e3;
    return first;
}

// The device's texture tiles: the command line's, else Option "limits" "texturememory",
// else (0) every tile when they fit in 256 MiB.
size_t textureCacheTiles(const RenderSettings& settings, const Scene& scene) {
    if (settings.textureCacheTiles > 0 || scene.render.textureMemoryKB <= 0)
        return settings.textureCacheTiles;
    return size_t(scene.render.textureMemoryKB) * 1024 /
           (sizeof(rt_float4) * RT_TEX_TILE_TEXELS);
}

// Truly displaced surfaces are moved before their tree is built, by the shading
// program: this waits for it, which is then returned.
std::optional<RenderPrograms> displaceBeforeTheTree(
    const ClContext& ctx, std::future<RenderPrograms>& programBuild, FrameScene& fs,
    const Features& f, const ShadingSetup& shading, TextureSet& textures, Profiler& prof,
    RenderStats& st, rib::Diagnostics& diag) {
    std::optional<RenderPrograms> built;
    if (fs.diced && !fs.surfaces.vertexCorner.empty()) {
        built.emplace(programBuild.get());
        const auto td = Clock::now();
        const DisplacementReport dr = displaceDicedSurfaces(
            ctx, built->shade->get(), prof, *fs.diced, fs.surfaces, f, shading, textures,
            fs.view, fs.view.perspective ? 0.0f : fs.view.pixelWidth);
        st.displacedVertices = dr.vertices;
        st.displaceMs = secondsSince(td) * 1e3;
        reportDisplacement(dr, *fs.diced, diag);
    }
    st.dicedTriangles = fs.surfaces.cornerVertex.size() / 3;
    return built;
}

// Every ray of the pool in pool order: the one shader's run, which is never sorted.
std::vector<uint32_t> poolOrder(size_t pool) {
    std::vector<uint32_t> order(pool);
    for (size_t i = 0; i < pool; ++i) order[i] = uint32_t(i);
    return order;
}

// The shaders' uniform work, once per instance, into the parameter blocks.
void prepareUniforms(const ClContext& ctx, const RenderPrograms& programs,
                     const ShadingSetup& shading, DeviceScene& ds, Profiler& prof) {
    if (shading.prepares.empty()) return;
    Kernel prepare(ctx, programs.shade->get(), "rd_prepare_uniforms", prof);
    prepare.launch(shading.prepares.size(), cl_uint(shading.prepares.size()), ds.params);
    prepare.collectActive();
}

// The treelet tracer, cut from the tree the program walks, where the features chose it
// (instead of the two intersect launches).
std::unique_ptr<TreeletTracer> treeletTracer(const ClContext& ctx,
                                             const RenderSettings& settings,
                                             const Scene& scene, const SceneBvh& bvh,
                                             cl_program trace, Profiler& prof,
                                             size_t treeletBudget, size_t pool,
                                             TreeletStats& stats) {
    const size_t sceneMemory = settings.sceneMemoryBytes > 0
                                   ? settings.sceneMemoryBytes
                                   : size_t(scene.render.sceneMemoryKB) << 10;
    return withTree(bvh, [&](const auto& tree) {
        return std::make_unique<TreeletTracer>(ctx, trace, prof, tree, treeletBudget,
                                               sceneMemory, pool, stats);
    });
}

PassTargets passTargets(const SamplingSettings& ss, const FrameBudgets& budgets,
                        const Features& f, const RenderSettings& settings,
                        uint32_t maxJob) {
    PassTargets t;
    t.pixelError = ss.pixelError;
    t.errorTarget = budgets.error;
    t.timeBudget = budgets.time;
    t.sobol = f.sobol;
    t.errorSeriesSec = settings.errorSeriesSec;
    t.maxJob = maxJob;
    return t;
}

FrameLimits frameLimits(const SamplingSettings& ss, const FrameBudgets& budgets,
                        const RenderSettings& settings, const Film& film, size_t pool) {
    FrameLimits l;
    l.pool = pool;
    l.timeBudget = budgets.time;
    l.errorTarget = budgets.error;
    // Passes overlap when a pass can follow the first.
    l.overlapPasses =
        settings.overlapPasses && (ss.maxSamples > ss.minSamples || budgets.error > 0);
    l.plannedSamples = double(film.cropPixelCount() * ss.maxSamples);
    return l;
}

}  // namespace

Renderer::Renderer(const ClContext& ctx, const RenderSettings& settings)
    : m_ctx(ctx), m_settings(settings) {}

RenderStats Renderer::render(const Scene& input, Film& film, rib::Diagnostics& diag) {
    const auto t0 = Clock::now();
    RenderStats st;
    FrameScene frameScene = diceTrueDisplacement(input, diag);
    const Scene& scene = frameScene.diced ? *frameScene.diced : input;
    st.device = m_ctx.name();
    st.platform = m_ctx.info().platformName;
    st.threadsPinned = m_ctx.info().isPocl() && poclThreadsPinned();
    // The scene's RSL shaders, compiled and bound: they decide lights, trace and more;
    // the textures they may ask for; the features the kernels need.
    const std::vector<std::string> aovNames = frameAovNames(scene, m_settings);
    ShadingSetup shading = ShaderSet(scene, diag).prepare(aovNames);
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
    const FrameBudgets budgets = frameBudgets(m_settings, scene);

    // The pool and its sample slots (kSlotsPerRay a ray); the first pass planned on
    // another thread while the programs and the BVH are built.
    const PoolShape shape = poolShapeOf(f, shading, m_ctx, m_settings.poolCapacity);
    st.poolCapacity = shape.capacity;
    st.poolBytesPerRay = shape.bytesPerRay();
    SampleRing ring(RayPool::kSlotsPerRay * shape.capacity);
    const Camera cam0 = scene.deviceCamera();
    scene.camera.cropPixels(film.cropX0, film.cropX1, film.cropY0, film.cropY1);
    const SamplingSettings ss = frameSampling(scene, m_settings, cam0, film,
                                              budgets.time > 0 || budgets.error > 0);
    std::optional<SamplePlanner> planner;
    const bool testsOnDevice =
        m_settings.devicePixelTests && m_ctx.info().fp64 &&
        size_t(cam0.width) * size_t(cam0.height) >= m_settings.devicePixelTestsFrom;
    std::future<FirstPass> firstPass = std::async(std::launch::async, [&] {
        return planFirstPass(planner, cam0, film, ss, budgets.error, shape, ring,
                             testsOnDevice);
    });

    // Scene -> BVH -> specialised programs (trace, shading) -> device arrays. The programs
    // build on another thread while the BVH is built: neither needs the other (a cold
    // build is a second or more of the compiler, a warm one 40-60 ms on PoCL).
    std::future<RenderPrograms> programBuild = std::async(
        std::launch::async, [&] { return RenderPrograms(m_ctx, shading, buildOptions(f)); });
    textures.createDevice(m_ctx, f.textures ? textureCacheTiles(m_settings, scene) : 1);
    Profiler prof(m_ctx);
    if (m_settings.timeline) prof.keepTimeline();
    std::optional<RenderPrograms> builtEarly = displaceBeforeTheTree(
        m_ctx, programBuild, frameScene, f, shading, textures, prof, st, diag);
    auto tb = Clock::now();
    SceneBvh sceneBvh = buildSceneBvh(scene, f.bvhWidth);
    st.bvhBuildMs = secondsSince(tb) * 1e3;
    countScene(scene, sceneBvh, st);
    // The device's arrays and the ray pool while the programs build (a warm build of the
    // two is 60-70 ms on PoCL, most of it its preprocessor)
    DeviceScene ds(m_ctx, scene, sceneBvh, f, shading);
    RayPool rp(m_ctx, shape.capacity, shape.spawn, shape.shadowSlots, ring.slotCapacity(),
               f.aovs, f.motion, f.instances, shape.shaderCount + 1, shape.weightFloats,
               shape.aovFloats, shape.rayAovFloats, shape.shaderShadows);
    if (shape.shaderCount == 1) rp.sorted.upload(poolOrder(shape.capacity));
    const RenderPrograms programs =
        builtEarly ? std::move(*builtEarly) : programBuild.get();
    st.program = programs.info();
    st.traceProgram = programs.trace->info();
    st.shadeProgram = programs.shade->info();
    RenderKernels k(m_ctx, programs.trace->get(), programs.shade->get(), prof,
                    shading.shadeKernels);
    if (f.shadowPackets) k.intersectShadow.setLanesPerItem(RT_PACKET_RAYS);
    if (f.closestPackets) k.intersectClosest.setLanesPerItem(RT_PACKET_RAYS);
    prepareUniforms(m_ctx, programs, shading, ds, prof);
    const std::unique_ptr<TreeletTracer> treelets =
        f.treelets
            ? treeletTracer(m_ctx, m_settings, scene, sceneBvh, programs.trace->get(),
                            prof, treeletBudget, shape.capacity, st.treelets)
            : nullptr;
    const TraceScene traceScene{ds.quadrics,      ds.csg,    ds.triangles, ds.quadricMotion,
                                ds.trianglesEnd, rp.sample, rp.sampleTime};
    const ShadowSurfaces shadowSurfaces{ds.attrs,  ds.materials,          ds.materialChannels,
                                        rp.shAov,  f.maxTransparentDepth, rp.slotRays};
    // The lists of points to shade again once the tiles they missed are there.
    TextureReshade reshade(m_ctx, textures, shape.capacity, shape.shaderCount,
                           f.textures);

    // The film, zeroed. Its buffers are the film's own memory (on a CPU device; a GPU
    // copies it at each sync). The host reads them after syncToHost only, when no kernel
    // that writes them is in flight: the round's finish precedes every sync, and planning
    // runs between passes.
    const Camera& cam = ds.camera;
    clearFilm(film, cam, scene, shading, f);
    DeviceBuffer<PixelAccum> filmBuf(m_ctx, film.pixels);
    DeviceBuffer<AovAccum> aovBuf(m_ctx, film.aovs);
    DeviceBuffer<float> shaderAovBuf(m_ctx, film.shaderAovSums);
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

    // The passes, streamed through the pool in rounds (render_loop.h), then the end of
    // the frame (frame_finish.h).
    PassPlanning planning(passTargets(ss, budgets, f, m_settings, shape.maxJob()), film,
                          filmBuf, planner, ring, prof, st, t0, [&] {
                              return uint64_t(k.intersectClosest.peekActive() +
                                              k.intersectShadow.peekActive() +
                                              (treelets ? treelets->peekRays() : 0));
                          });
    const FrameDevice device{
        m_ctx, scene,          f,          shading,        ds,           rp,
        k,     treelets.get(), traceScene, shadowSurfaces, textures,     reshade,
        prof,  ring,           filmBuf,    aovBuf,         shaderAovBuf, numerics};
    RenderLoop loop(device, m_settings,
                    frameLimits(ss, budgets, m_settings, film, shape.capacity), planning,
                    *planner, st, t0);
    loop.run(std::move(first->jobs), std::move(first->refill), first->planMs);
    first.reset();
    finishFrame(device,
                FrameEnd{film, programs.shade->get(), pixelTests ? &*pixelTests : nullptr,
                         filmSums ? &*filmSums : nullptr, *planner, ss.maxSamples >= 2},
                st, diag, t0);
    return st;
}

}  // namespace rd
