// renderer.cpp: the render loop. It reads as the algorithm: analyse the scene, build the
// BVH and the specialised program, upload; then pass after pass of the sample plan, each
// in batches that fill the ray pool: refill (generate_eye), trace (intersect_closest),
// shade, trace shadows (intersect_shadow), add them (accumulate_shadows), retire
// (retire_samples). Between launches it polls the stop conditions; a batch cut short is
// dropped whole, so the film holds only whole samples.
#include "renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <memory>

#include "cl/include/ray.h"
#include "device_scene.h"
#include "imager_stage.h"
#include "texture_reshade.h"
#include "scene_bvh.h"
#include "film/film_error.h"
#include "progress.h"
#include "shaders/shader_set.h"
#include "stop.h"

namespace rd {

// numerics.clh: RT_NUM_PROCEDURAL_BASE, the first archive flag after the counters
constexpr size_t kProceduralFlags = 8;
namespace {

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

const std::vector<std::string> kRenderSources = {
    "generate_eye.cl", "intersect.cl", "sort_by_shader.cl", "accumulate.cl", "compact.cl",
    "retire.cl", "treelet.cl"};

// The ray pool. The current round's rays (each knows its sample), the rays the shade
// stage spawns (slot i: ray i's continuation), light_count shadow slots per ray, the
// compaction's per-group counts, and the per-sample AOV record only when AOVs are on.
struct RayPool {
    RayPool(const ClContext& ctx, size_t capacity, size_t spawn, uint32_t shadowLights,
            bool aovs, bool motion, bool instances, size_t shaderKeys)
        : origin(ctx, capacity), direction(ctx, capacity), weight(ctx, capacity),
          state(ctx, capacity), sample(ctx, capacity), hits(ctx, capacity),
          totals(ctx, capacity), nextOrigin(ctx, capacity * spawn),
          nextDirection(ctx, capacity * spawn), nextWeight(ctx, capacity * spawn),
          nextState(ctx, capacity * spawn), nextSample(ctx, capacity * spawn),
          groupLive(ctx, capacity * spawn / 64 + 1), groupOffset(ctx, capacity * spawn / 64 + 1),
          key(ctx, capacity), keyCount(ctx, shaderKeys), keyCursor(ctx, shaderKeys),
          sorted(ctx, capacity),
          shOrigin(ctx, capacity * shadowLights), shDirection(ctx, capacity * shadowLights),
          shWeight(ctx, capacity * shadowLights), shState(ctx, capacity * shadowLights),
          aov(ctx, aovs ? capacity : 0), samplePixel(ctx, capacity),
          sampleIndex(ctx, capacity), batchPixel(ctx, capacity),
          batchFirst(ctx, capacity + 1), sampleTime(ctx, motion ? capacity : 0),
          hitInstance(ctx, instances ? capacity : 0) {
        shState.fillZero();
        nextState.fillZero();
    }
    DeviceBuffer<rt_float4> origin, direction, weight;
    DeviceBuffer<RayState> state;
    DeviceBuffer<uint32_t> sample;
    DeviceBuffer<RayHit> hits;
    DeviceBuffer<SampleTotal> totals;
    DeviceBuffer<rt_float4> nextOrigin, nextDirection, nextWeight;
    DeviceBuffer<RayState> nextState;
    DeviceBuffer<uint32_t> nextSample;
    DeviceBuffer<uint32_t> groupLive, groupOffset;
    DeviceBuffer<uint32_t> key, keyCount, keyCursor, sorted;  // the sort by shader
    DeviceBuffer<rt_float4> shOrigin, shDirection, shWeight;
    DeviceBuffer<RayState> shState;
    DeviceBuffer<SampleAov> aov;
    DeviceBuffer<uint32_t> samplePixel, sampleIndex;  // the batch's samples
    DeviceBuffer<uint32_t> batchPixel, batchFirst;    // its pixels, CSR over the samples
    DeviceBuffer<float> sampleTime;                   // motion blur: each sample's time
    DeviceBuffer<uint32_t> hitInstance;               // instance of each closest hit
};

struct RenderKernels {
    RenderKernels(const ClContext& ctx, cl_program p, Profiler& prof,
                  const std::vector<std::string>& shadeKernels)
        : generateEye(ctx, p, "generate_eye", prof),
          intersectClosest(ctx, p, "intersect_closest", prof),
          classify(ctx, p, "classify_hits", prof),
          scatter(ctx, p, "scatter_by_shader", prof),
          intersectShadow(ctx, p, "intersect_shadow", prof),
          accumulateShadows(ctx, p, "accumulate_shadows", prof),
          compactCount(ctx, p, "compact_count", prof),
          compactScatter(ctx, p, "compact_scatter", prof),
          retire(ctx, p, "retire_samples", prof) {
        for (const std::string& name : shadeKernels)
            shade.push_back(std::make_unique<Kernel>(ctx, p, name, prof));
    }
    Kernel generateEye, intersectClosest, classify, scatter, intersectShadow,
        accumulateShadows, compactCount, compactScatter, retire;
    std::vector<std::unique_ptr<Kernel>> shade;  // one per compiled surface shader
    std::vector<Kernel*> all() {
        std::vector<Kernel*> v{&generateEye, &intersectClosest, &classify, &scatter,
                               &intersectShadow, &accumulateShadows, &compactCount,
                               &compactScatter, &retire};
        for (auto& s : shade) v.push_back(s.get());
        return v;
    }
};

// A batch: pixel-major list of samples, at most the pool's capacity.
struct Batch {
    std::vector<uint32_t> samplePixel, sampleIndex, pixel, first;
};

// Cuts a pass into batches of at most `capacity` samples; a pixel's samples stay
// contiguous within a batch (the retire kernel relies on it).
std::vector<Batch> makeBatches(const std::vector<PixelRequest>& pass, size_t capacity) {
    std::vector<Batch> out;
    Batch b;
    auto flush = [&] {
        if (b.samplePixel.empty()) return;
        b.first.push_back(uint32_t(b.samplePixel.size()));
        out.push_back(std::move(b));
        b = Batch();
    };
    for (const PixelRequest& r : pass) {
        uint32_t done = 0;
        while (done < r.count) {
            if (b.samplePixel.size() == capacity) flush();
            uint32_t take = uint32_t(std::min<size_t>(r.count - done,
                                                      capacity - b.samplePixel.size()));
            b.pixel.push_back(r.pixel);
            b.first.push_back(uint32_t(b.samplePixel.size()));
            for (uint32_t k = 0; k < take; ++k) {
                b.samplePixel.push_back(r.pixel);
                b.sampleIndex.push_back(r.first + done + k);
            }
            done += take;
        }
    }
    flush();
    return out;
}

const char* signalName(int sig) { return sig == 2 ? "SIGINT" : sig == 15 ? "SIGTERM" : "signal"; }

}  // namespace

Renderer::Renderer(const ClContext& ctx, const RenderSettings& settings)
    : m_ctx(ctx), m_settings(settings) {}

RenderStats Renderer::render(const Scene& scene, Film& film, rib::Diagnostics& diag) {
    const auto t0 = Clock::now();
    RenderStats st;
    st.device = m_ctx.name();
    st.platform = m_ctx.info().platformName;
    // The scene's RSL shaders, compiled and bound: they decide lights, trace and more.
    ShadingSetup shading = ShaderSet(scene, diag).prepare();
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
    shading.generated["rd_textures.cl"] = textures.deviceSource(
        scene.worldOrigin.x, scene.worldOrigin.y, scene.worldOrigin.z);
    Features f = analyse(scene, shading);
    f.textures = shading.textures && !textures.empty();
    f.aovs = m_settings.geometricAovs;
    // Treelet-streamed traversal when a budget is set and the scene allows it.
    const size_t treeletBudget = m_settings.treeletBytes > 0 ? m_settings.treeletBytes
                                                             : size_t(scene.render.treeletBytes);
    configureTreelets(f, m_ctx, treeletBudget, st.treelets);
    if (treeletBudget > 0 && !f.treelets)
        diag.warning(rib::SourceLoc{scene.sourceFile, 0},
                     "treelet budget not used: " + st.treelets.why);
    st.features = f;

    // Budgets: the command line wins over Option "render".
    const double timeBudget = m_settings.timeBudget > 0 ? m_settings.timeBudget
                                                        : scene.render.time;
    const double errorTarget = m_settings.errorTarget > 0 ? m_settings.errorTarget
                                                          : scene.render.error;

    // Scene -> BVH -> specialised program -> device arrays
    auto tb = Clock::now();
    SceneBvh sceneBvh = buildSceneBvh(scene);
    const Bvh4& bvh4 = sceneBvh.bvh4;
    st.bvhBuildMs = secondsSince(tb) * 1e3;
    st.triangles = scene.triangles.size();
    for (const Quadric& q : scene.quadrics) {
        if (q.kind == RT_Q_CSG) ++st.csgSolids;
        else if (q.kind == RT_Q_INSTANCE) ++st.instances;
        else if (q.kind != RT_Q_MOVING_TRIANGLE) ++st.quadrics;
    }
    st.sceneBytes = bvh4.nodes.size() * sizeof(Bvh4Node) + bvh4.blocks.size() * sizeof(Triangle4) +
                    scene.triangles.size() * (sizeof(Triangle) + sizeof(TriangleAttr)) +
                    scene.normals.size() * sizeof(rt_float4) +
                    scene.quadrics.size() * sizeof(Quadric) + scene.csg.size() * 4;
    st.bvhNodes = bvh4.nodes.size();
    st.droppedPrims = sceneBvh.droppedPrims;
    std::vector<std::string> sources = kRenderSources;
    sources.insert(sources.end(), shading.sourceOrder.begin(), shading.sourceOrder.end());
    Program program(m_ctx, assembleClSource(sources, shading.generated), buildOptions(f));
    st.program = program.info();
    Profiler prof(m_ctx);
    RenderKernels k(m_ctx, program.get(), prof, shading.shadeKernels);
    DeviceScene ds(m_ctx, scene, bvh4, sceneBvh.objects, f, shading);
    if (!shading.prepares.empty()) {  // the shaders' uniform work, once per instance
        Kernel prepare(m_ctx, program.get(), "rd_prepare_uniforms", prof);
        prepare.launch(shading.prepares.size(), cl_uint(shading.prepares.size()), ds.params);
        prepare.collectActive();
    }
    const Camera& cam = ds.camera;
    std::unique_ptr<TreeletTracer> treelets;  // instead of the two intersect launches

    const uint32_t nl = f.shadowRays ? f.lightCount : 0;
    const size_t spawn = size_t(f.spawnSlots());
    const cl_uint shaderCount = cl_uint(shading.shadeKernels.size());
    // The pool holds a batch's rays and what they spawn: keep it within a memory budget.
    const size_t bytesPerRay = 128 + spawn * 72 + size_t(nl) * 64;
    const size_t pool = std::clamp<size_t>(std::min(m_settings.poolCapacity,
                                                    (size_t(512) << 20) / bytesPerRay),
                                           64, std::max<size_t>(64, m_settings.poolCapacity));
    st.poolCapacity = pool;
    RayPool rp(m_ctx, pool, spawn, nl, f.aovs, f.motion, f.instances, shaderCount + 1);
    if (f.treelets)
        treelets = std::make_unique<TreeletTracer>(
            m_ctx, program.get(), prof, bvh4, treeletBudget,
            m_settings.sceneMemoryBytes > 0 ? m_settings.sceneMemoryBytes
                                            : size_t(scene.render.sceneMemoryKB) << 10,
            pool, st.treelets);
    const TraceScene traceScene{ds.quadrics,      ds.csg,    ds.triangles, ds.quadricMotion,
                                ds.trianglesEnd, rp.sample, rp.sampleTime};
    // Textures: the device tile cache (Option "limits" "texturememory" or the command
    // line; else every tile when they fit in 256 MiB), and the lists of points to shade
    // again once the tiles they missed are there.
    size_t cacheTiles = m_settings.textureCacheTiles;
    if (cacheTiles == 0 && scene.render.textureMemoryKB > 0)
        cacheTiles = size_t(scene.render.textureMemoryKB) * 1024 /
                     (sizeof(rt_float4) * RT_TEX_TILE_TEXELS);
    textures.createDevice(m_ctx, f.textures ? cacheTiles : 1);
    TextureReshade reshade(m_ctx, textures, pool, shaderCount, f.textures);
    const size_t npix = size_t(cam.width) * size_t(cam.height);
    film.width = cam.width;
    film.exposureGain = scene.camera.exposure[0];
    film.exposureGamma = scene.camera.exposure[1];
    film.height = cam.height;
    DeviceBuffer<PixelAccum> filmBuf(m_ctx, npix);
    filmBuf.fillZero();
    DeviceBuffer<AovAccum> aovBuf(m_ctx, f.aovs ? npix : 0);
    aovBuf.fillZero();
    // numerics.clh RT_NUM_* counters, then a flag per archive not loaded yet
    DeviceBuffer<uint32_t> numerics(m_ctx, kProceduralFlags + scene.procedurals.size());
    numerics.fillZero();
    film.pixels.assign(npix, PixelAccum{});
    st.sceneSetupMs = secondsSince(t0) * 1e3;

    SamplingSettings ss;
    ss.firstPassBlock = m_settings.firstPassBlock > 0 ? m_settings.firstPassBlock
                                                      : scene.render.firstPassBlock;
    ss.pixelError = scene.render.pixelError;
    const bool openEnded = timeBudget > 0 || errorTarget > 0;
    ss.maxSamples = openEnded ? 1u << 16 : uint32_t(cam.spp_x * cam.spp_y);
    ss.minSamples = std::min(2u, ss.maxSamples);
    scene.camera.cropPixels(film.cropX0, film.cropX1, film.cropY0, film.cropY1);
    SamplePlanner planner(cam.width, cam.height, film.cropX0, film.cropX1, film.cropY0,
                          film.cropY1, ss);
    Progress progress(m_settings.progress);

    auto stopNow = [&] {
        if (int sig = stopSignal()) {
            st.stopReason = signalName(sig);
            return true;
        }
        // The first batch always completes, so a budget smaller than the set-up time still
        // yields an image (at the cost of overrunning it by one short batch).
        if (timeBudget > 0 && st.batches > 0 && secondsSince(t0) >= timeBudget) {
            st.stopReason = "time budget";
            return true;
        }
        return false;
    };
    // Returns false when a stop cut the batch short (its samples are then dropped).
    // Compacts the rays the shade stage spawned into the current round's buffers and
    // returns how many there are: group counts on the device, their prefix on the host.
    auto compactSpawned = [&](cl_uint n) {
        k.compactCount.launch(n, n, rp.nextState, rp.groupLive);
        const size_t groups = (n + 63) / 64;
        std::vector<uint32_t> live = rp.groupLive.download();
        std::vector<uint32_t> offset(live.size(), 0);
        uint32_t total = 0;
        for (size_t g = 0; g < groups; ++g) offset[g] = total, total += live[g];
        if (total == 0) return cl_uint(0);
        if (total > pool) st.overflowRays += total - pool;  // dropped: reported at the end
        rp.groupOffset.upload(offset);
        k.compactScatter.launch(n, n, cl_uint(pool), rp.groupOffset, rp.nextOrigin, rp.nextDirection,
                                rp.nextWeight, rp.nextState, rp.nextSample, rp.origin,
                                rp.direction, rp.weight, rp.state, rp.sample);
        return cl_uint(std::min<size_t>(total, pool));
    };
    // One shade kernel per shader over its run [offsets[s], + counts[s]) of `sorted`;
    // points a texture miss sends back are listed in `retry` at the same offsets.
    auto shadeRuns = [&](const std::vector<uint32_t>& counts, const std::vector<uint32_t>& offsets,
                         const DeviceBuffer<uint32_t>& sorted, DeviceBuffer<uint32_t>& retry) {
        for (cl_uint s = 0; s < shaderCount; ++s) {
            if (counts[s] == 0) continue;
            k.shade[s]->launch(counts[s], cl_uint(offsets[s]), cl_uint(counts[s]), sorted,
                               ds.triangles, ds.attrs, ds.normals, ds.vertexSt, ds.vertexCs,
                               ds.vertexOs, ds.materials, ds.quadrics, ds.quadricPrimvars,
                               ds.quadricMotion, ds.trianglesEnd, rp.sampleTime, rp.samplePixel,
                               rp.sampleIndex, rp.hitInstance, ds.params, rp.origin,
                               rp.direction, rp.weight, rp.state, rp.sample, rp.hits, rp.totals,
                               rp.nextOrigin, rp.nextDirection, rp.nextWeight, rp.nextState,
                               rp.nextSample, rp.shOrigin, rp.shDirection, rp.shWeight,
                               rp.shState, rp.aov, nl, numerics, textures.infoBuf,
                               textures.pageBuf, textures.tileBuf, textures.requestBuf,
                               textures.counterBuf, textures.usedBuf, retry, reshade.counts(), s);
        }
    };
    // Returns false when a stop cut the batch short (its samples are then dropped).
    auto traceBatch = [&](const Batch& b) {
        cl_uint n = cl_uint(b.samplePixel.size());
        const cl_uint pixels = cl_uint(b.pixel.size());
        rp.samplePixel.upload(b.samplePixel);
        rp.sampleIndex.upload(b.sampleIndex);
        rp.batchPixel.upload(b.pixel);
        rp.batchFirst.upload(b.first);
        k.generateEye.launch(n, ds.cameraBuf, n, rp.samplePixel, rp.sampleIndex, rp.origin,
                             rp.direction, rp.weight, rp.state, rp.sample, rp.totals, rp.aov,
                             rp.sampleTime);
        // Rounds: trace, shade, shadows; then the spawned rays (continuations through
        // Opacity < 1) are compacted and traced in the next round, until none is left.
        const int rounds = 1 + (f.transparency ? f.maxTransparentDepth : 0) +
                           (f.trace ? f.maxSpecularDepth : 0);
        for (int round = 0; round < rounds && n > 0; ++round) {
            if (stopNow()) return false;
            if (treelets)
                treelets->closest(n, rp.origin, rp.direction, rp.state, rp.hits, traceScene);
            else
                k.intersectClosest.launch(n, n, ds.nodes, ds.blocks, rp.origin, rp.direction,
                                          rp.state, rp.hits, ds.quadrics, ds.csg, ds.triangles,
                                          ds.quadricMotion, ds.trianglesEnd, rp.sample,
                                          rp.sampleTime, rp.hitInstance);
            // Sort the hits by shader, then run each shader over its own run of rays.
            rp.keyCount.fillZero();
            k.classify.launch(n, n, shaderCount, nl, rp.hits, ds.attrs, ds.materials, ds.quadrics, rp.hitInstance, rp.key,
                              rp.keyCount, rp.nextState, rp.shState);
            std::vector<uint32_t> counts = rp.keyCount.download(), offsets(counts.size(), 0);
            for (size_t s = 1; s < counts.size(); ++s) offsets[s] = offsets[s - 1] + counts[s - 1];
            rp.keyCursor.upload(offsets);
            k.scatter.launch(n, n, shaderCount, rp.key, rp.keyCursor, rp.sorted);
            shadeRuns(counts, offsets, rp.sorted, reshade.firstList());
            if (f.textures) reshade.run(offsets, shading.surfaceNames, shadeRuns);
            if (nl > 0) {
                if (treelets)
                    treelets->shadow(cl_uint(n * nl), rp.shOrigin, rp.shDirection, rp.shState,
                                     traceScene, nl);
                else
                    k.intersectShadow.launch(size_t(n) * nl, cl_uint(n * nl), ds.nodes,
                                             ds.blocks, rp.shOrigin, rp.shDirection,
                                             rp.shState, ds.quadrics, ds.csg, ds.triangles,
                                             ds.quadricMotion, ds.trianglesEnd, rp.sample,
                                             rp.sampleTime, nl, numerics);
                k.accumulateShadows.launch(n, n, nl, rp.sample, rp.shWeight, rp.shState,
                                           rp.totals);
            }
            if (round + 1 < rounds) n = compactSpawned(cl_uint(n * spawn));
        }
        if (stopNow()) return false;
        k.retire.launch(pixels, pixels, rp.batchPixel, rp.batchFirst, rp.totals, filmBuf,
                        rp.aov, aovBuf);
        return true;
    };

    // Batches are sized to about a quarter second once the speed is known, so a stop or
    // a time budget is honoured promptly and the error series is sampled often.
    size_t batchCap = std::min<size_t>(pool, 16384);
    double samplesPerSec = 0;
    double lastSample = -1;
    auto sampleError = [&](bool force) {
        double now = secondsSince(t0);
        if (!force && now - lastSample < 0.5) return;
        lastSample = now;
        film.pixels = filmBuf.download();
        st.estimatedError = estimateFilmError(film.pixels);
        prof.collect();
        uint64_t rays = k.intersectClosest.peekActive() + k.intersectShadow.peekActive() +
                        (treelets ? treelets->peekRays() : 0);
        st.errorVsTime.push_back({now, rays, st.estimatedError});
    };

    bool stopped = false;
    while (!stopped) {
        float pixelError = ss.pixelError;
        if (errorTarget > 0) pixelError = float(errorTarget);
        else if (timeBudget > 0 && st.estimatedError > 0)
            pixelError = float(0.5 * st.estimatedError);  // refine the worse half
        std::vector<PixelRequest> pass = planner.nextPass(film.pixels, pixelError);
        if (pass.empty()) {
            st.stopReason = "quality";
            break;
        }
        ++st.passes;
        size_t done = 0;
        while (done < pass.size() && !stopped) {
            // Take pixels until the batch holds batchCap samples (fewer when the time
            // budget has less than a quarter second left: a batch cut short is wasted).
            size_t cap = batchCap;
            if (timeBudget > 0 && samplesPerSec > 0) {
                double left = timeBudget - secondsSince(t0);
                cap = std::clamp<size_t>(size_t(samplesPerSec * left * 0.9), 256, batchCap);
            }
            size_t end = done, samples = 0;
            while (end < pass.size() && samples < cap) samples += pass[end++].count;
            std::vector<PixelRequest> part(pass.begin() + long(done), pass.begin() + long(end));
            done = end;
            for (const Batch& b : makeBatches(part, pool)) {
                auto tBatch = Clock::now();
                if (!traceBatch(b)) {
                    st.abortedSamples += b.samplePixel.size();
                    stopped = true;
                    break;
                }
                m_ctx.finish();
                if (f.procedurals) {  // a ray reached an archive's bound: load it first
                    std::vector<uint32_t> flags = numerics.download();
                    for (size_t k = 0; k < scene.procedurals.size(); ++k)
                        if (flags[kProceduralFlags + k])
                            st.proceduralsReached.push_back(scene.procedurals[k].key);
                    if (!st.proceduralsReached.empty()) {
                        st.stopReason = "archives to load";
                        stopped = true;
                        break;
                    }
                }
                ++st.batches;
                st.eyeRays += b.samplePixel.size();
                double dt = secondsSince(tBatch);
                if (dt > 0) samplesPerSec = double(b.samplePixel.size()) / dt;
                batchCap = std::clamp<size_t>(size_t(samplesPerSec * 0.25), 1024, pool);
                sampleError(false);
                double fraction =
                    timeBudget > 0 ? secondsSince(t0) / timeBudget
                    : errorTarget > 0 && st.estimatedError > 0
                        ? std::min(1.0, std::log(1.0 / st.estimatedError) /
                                            std::log(1.0 / errorTarget))
                        : double(st.eyeRays) / double(film.cropPixelCount() * ss.maxSamples);
                progress.update(fraction, secondsSince(t0), st.eyeRays, st.estimatedError);
            }
        }
        if (stopped) break;
        sampleError(true);
        if (errorTarget > 0 && st.estimatedError >= 0 && st.estimatedError <= errorTarget) {
            st.stopReason = "error target";
            break;
        }
    }
    progress.finish();
    if (shading.imager) {  // the Imager shader on the finished image (also a stopped one)
        film.pixels = filmBuf.download();
        film.imaged = applyImager(m_ctx, program.get(), prof, film, ds.params);
    }
    m_ctx.finish();
    prof.collect();
    for (Kernel* kern : k.all()) kern->collectActive();
    if (treelets) treelets->collectActive();
    st.kernels = prof.stats();
    if (f.textures) {
        std::vector<uint32_t> tc = textures.counterBuf.download();
        textures.stats().lookups = tc[1];
        textures.stats().missedLookups = tc[2];
        st.textures = textures.stats();
    }
    auto active = [&](const char* name) {
        auto it = st.kernels.find(name);
        return it == st.kernels.end() ? uint64_t(0) : it->second.activeItems;
    };
    // Eye rays of dropped batches were traced too; count what the device did.
    st.eyeRays += st.abortedSamples;
    // (the treelet path's first rounds take each ray once, as the intersect kernels do)
    const uint64_t closestRays = active("intersect_closest") + active("treelet_closest_root");
    st.continuationRays = closestRays > st.eyeRays ? closestRays - st.eyeRays : 0;
    st.shadowRays = active("intersect_shadow") + active("treelet_shadow_root");
    film.pixels = filmBuf.download();
    if (f.aovs) film.aovs = aovBuf.download();
    st.estimatedError = estimateFilmError(film.pixels);
    st.nonfiniteSamples = film.nonfiniteCount();
    std::vector<uint32_t> num = numerics.download();
    st.shadeNonfinite = num[0], st.shadeNegative = num[1], st.shadeHuge = num[2];
    st.shadeDenormal = num[3], st.transparentDepthCut = num[4], st.specularDepthCut = num[5];
    st.rouletteEnded = num[6];
    const rib::SourceLoc where{scene.sourceFile, 0};
    if (st.shadeNonfinite + st.shadeNegative + st.shadeHuge > 0)
        diag.warning(where, "shaders produced " + std::to_string(st.shadeNonfinite) +
                                " NaN/Inf, " + std::to_string(st.shadeNegative) +
                                " negative and " + std::to_string(st.shadeHuge) +
                                " huge (> 1e10) results; left out of the image");
    if (st.overflowRays > 0)
        diag.warning(where, std::to_string(st.overflowRays) +
                                " traced ray(s) dropped: more in flight than the ray pool holds "
                                "(lower maxspeculardepth or trace fewer rays per hit)");
    if (st.transparentDepthCut > 0)
        diag.warning(where, std::to_string(st.transparentDepthCut) +
                                " ray(s) stopped after " + std::to_string(f.maxTransparentDepth) +
                                " transparent surfaces; raise Attribute \"trace\" "
                                "\"maxtransparentdepth\"");
    st.unsampledPixels = film.unsampledCount();
    st.passes = planner.passes();
    st.elapsedSec = secondsSince(t0);
    // Pool fill: rays traced per intersect_closest launch over the pool's capacity.
    // Device busy: kernel time over the sampling loop's wall time; the rest is the device
    // waiting on the host (its downloads, sorts' offsets, batch planning) or idle.
    if (auto it = st.kernels.find(treelets ? "treelet_closest_root" : "intersect_closest");
        it != st.kernels.end() && it->second.launches > 0)
        st.poolFill = double(it->second.activeItems) /
                      (double(it->second.launches) * double(st.poolCapacity));
    double deviceMs = 0;
    for (const auto& [name, ks] : st.kernels) deviceMs += ks.deviceMs;
    const double loopMs = st.elapsedSec * 1e3 - st.sceneSetupMs;
    if (loopMs > 0) st.deviceBusy = std::min(1.0, deviceMs / loopMs);
    st.errorVsTime.push_back({st.elapsedSec, st.totalRays(), st.estimatedError});
    return st;
}

}  // namespace rd
