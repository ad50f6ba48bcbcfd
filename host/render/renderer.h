// renderer.h: the render loop of DESIGN.md section 3 for one Scene on one device: upload
// the scene and its BVH, then pass after pass of adaptive sampling, streamed through the
// ray pool in rounds: refill with eye samples, trace and shade, trace shadow rays, retire
// whole samples to the film; stop on quality, error target, time budget or signal.
#pragma once
#include <array>
#include <map>
#include <string>
#include <vector>

#include "texture/texture_set.h"
#include "features.h"
#include "film/film.h"
#include "ocl/context.h"
#include "ocl/kernel.h"
#include "ocl/program.h"
#include "sampling.h"
#include "treelet_trace.h"
#include "scene/scene.h"

namespace rd {

struct RenderSettings {
    int bvhWidth = 0;         // resident BVH nodes: 4, 8 or 16 wide; 0: by device (features.h)
    bool shadowPackets = true;   // shadow rays in packets where the scene allows (features.h)
    bool closestPackets = true;  // coherent closest-hit rays in packets, likewise
    size_t poolCapacity = 0;  // rays per round; 0: 16k per compute unit within a memory budget
    // The most jobs one retire_samples launch takes (a larger window takes several); 0:
    // the device's (on PoCL 65472: it compiles a kernel again for its first launch of
    // 65536 work-items or more after smaller ones; else all).
    size_t retireLaunchItems = 0;
    // Plan the next adaptive pass while the last one's tail drains (its pixels in flight
    // wait a pass), so that eye rays keep the pool full; false: each pass drains first.
    bool overlapPasses = true;
    // Queue the next round's eye rays (at the pool's front) and the compaction of the
    // spawned rays (behind them) before the round's wait, so that the device does not
    // idle while the host wakes up; false: both after it (the rays as many as fit).
    bool pipelineRounds = true;
    // A pass asking for fewer samples than a 64th of the frame's pixels gives its pixels
    // two more doublings at once (SamplingSettings::smallPass); false: every pass doubles.
    bool jumpSmallPasses = true;
    // The adaptive passes that test every pixel (the first) do so on the device where it
    // has double precision (device_pixel_tests.h), and the film's error estimate at the
    // end of the frame is summed there (device_film_sums.h), for frames of at least
    // devicePixelTestsFrom pixels; false: on the host. The same passes and estimates.
    // (A smaller frame's test takes the host under a millisecond, less than a cold
    // compile of the four kernels, 0.3 s, or their launches and waits.)
    bool devicePixelTests = true;
    size_t devicePixelTestsFrom = 65536;
    double timeBudget = 0;    // seconds; 0 = none (also from Option "render" "time")
    double errorTarget = 0;   // relative film error; 0 = none ("render" "error")
    int firstPassBlock = 0;   // 0 = the scene's option (default 2: 1/4 ray per pixel)
    bool geometricAovs = false;  // render z and N
    // AOVs beyond the scene's (--aov): geometric ones, or shaders' output variables
    std::vector<std::string> extraAovs;
    bool progress = false;       // progress bar on stderr (when it is a terminal)
    size_t textureCacheTiles = 0;  // device texture tiles (0: the scene's, else all that fit)
    // Treelet-streamed traversal (treelet_trace.h): treelet budget in bytes (0: the
    // scene's Option "limits" "treeletbytes", else the resident traversal), and the device
    // bytes the BVH may take (0: the scene's "scenememory", else all: treelets resident).
    size_t treeletBytes = 0;
    size_t sceneMemoryBytes = 0;
    bool timeline = false;  // keep every kernel run in RenderStats::timeline (--timeline)
    // Seconds between the points of --stats' error-against-time series (each a pass over
    // the film) when no error target or time budget estimates the error every pass. It
    // never changes the image.
    double errorSeriesSec = 0.5;
    int seed = -1;          // which random numbers; -1: the scene's Option "render" "seed"
    int sobol = -1;         // Sobol samples (1) or independent (0); -1: the scene's "sampler"
};

// One point of the error-against-time series in --stats.
struct ErrorSample {
    double seconds;
    uint64_t rays;
    double estimatedError;  // < 0: not known yet
};

// One point of the pool-fill series in --stats: rays of a round over the capacity.
struct PoolFillSample {
    double seconds;
    double fill;
};

struct RenderStats {
    double elapsedSec = 0;
    double sceneSetupMs = 0, bvhBuildMs = 0;
    uint64_t eyeRays = 0, continuationRays = 0, shadowRays = 0;
    uint64_t triangles = 0, quadrics = 0, csgSolids = 0, instances = 0, bvhNodes = 0;
    uint64_t droppedPrims = 0;
    // true displacement (true_displacement.h): diced triangles, vertices moved, the time
    uint64_t dicedTriangles = 0, displacedVertices = 0;
    double displaceMs = 0;
    uint64_t sceneBytes = 0;  // device bytes of geometry: BVH, blocks, triangles, quadrics
    uint64_t nonfiniteSamples = 0, unsampledPixels = 0, abortedSamples = 0;
    uint64_t filmSamples = 0;  // whole samples in the film (re-issued ones counted once)
    // Shader results dropped before they reached a sample or a ray weight (numerics.clh):
    // NaN/Inf, negative, huge (> 1e10); denormal channels flushed to zero; rays cut by
    // maxtransparentdepth and by maxspeculardepth.
    uint64_t shadeNonfinite = 0, shadeNegative = 0, shadeHuge = 0, shadeDenormal = 0;
    uint64_t transparentDepthCut = 0, specularDepthCut = 0;
    uint64_t rouletteEnded = 0;  // trace() rays Russian roulette ended
    uint64_t traceCallsIgnored = 0;  // trace() calls past the most a shaded point records
    uint64_t shaderLoopsCut = 0;     // shading points where a loop ran past kShaderLoopPasses
    uint64_t overflowRays = 0;  // spawned rays beyond the pool and its spill stack: dropped
    uint64_t spilledRays = 0;   // spawned rays that waited on the spill stack
    uint64_t reissuedSamples = 0;  // samples aborted (a ray dropped) and traced again
    uint64_t retiredSamples = 0;   // samples that reached the film
    int bvhWidth = 0;         // resident BVH nodes: 4, 8 or 16 wide; 0: by device (features.h)
    size_t poolCapacity = 0;
    size_t poolBytesPerRay = 0;  // device bytes a ray of capacity takes (RayPool::bytesPerRay)
    double poolFill = 0;    // mean rays per round / pool capacity
    double deviceBusy = 0;  // kernel time / wall time of the sampling loop
    double hostOverhead = 0;  // sampling-loop time the device did not run kernels / frame
    double launchGapsMs = 0;  // of which: idle between kernels queued back to back
    double hostSyncOverhead = 0;  // the rest (the host's waits and work) / frame
    double planMs = 0;  // of which between passes: the film read back, the next pass planned
    std::vector<PoolFillSample> poolFillSeries;
    int passes = 0, iterations = 0;  // iterations: rounds of the ray pool
    int overlappedPasses = 0;  // passes planned while the last one's tail was in flight
    double estimatedError = -1;
    std::string stopReason;  // "quality", "error target", "time budget", "SIGINT", ...
    std::vector<ErrorSample> errorVsTime;
    Features features;
    ProgramBuildInfo program;  // the two programs as one (render_programs.h)
    ProgramBuildInfo traceProgram, shadeProgram;
    std::string device, platform;
    bool threadsPinned = false;  // PoCL's worker threads pinned (pinPoclThreadsByDefault)
    std::map<std::string, KernelStats> kernels;
    std::vector<TimelineEvent> timeline;  // every kernel run (RenderSettings::timeline)
    TextureStats textures;
    TreeletStats treelets;
    // DelayedReadArchive calls (keys) rays reached before they were loaded: the render
    // stopped at once; read the RIB again with them loaded (render_with_archives.h)
    std::vector<std::string> proceduralsReached;
    size_t archivesLoaded = 0;  // DelayedReadArchive calls read because rays reached them
    uint64_t totalRays() const { return eyeRays + continuationRays + shadowRays; }
};

class Renderer {
public:
    Renderer(const ClContext& ctx, const RenderSettings& settings);
    // Renders `scene` into `film` (sized from the scene's Format) and returns the figures
    // for --stats. A stop (time, signal) still leaves a valid film of the retired samples.
    // Throws on OpenCL errors.
    // Shader problems (not found, compile errors) are reported to `diag` and the
    // render goes on with defaultsurface.
    RenderStats render(const Scene& scene, Film& film, rib::Diagnostics& diag);

private:
    const ClContext& m_ctx;
    RenderSettings m_settings;
};

}  // namespace rd
