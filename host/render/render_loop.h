// render_loop.h: the passes and their rounds (DESIGN.md section 3), once the frame is set
// up (renderer.cpp). A pass's pixel jobs stream through the ray pool in rounds: refill
// the free end of the pool with eye rays (refill.h), trace, sort by shader, shade, trace
// shadows (render_round.cpp: traceRound); then close the round, retire the samples with
// no ray left and compact what the shaders spawned into the next round, read back at the
// round's one wait (render_round.cpp: finishRound). When a pass's queue is about to run
// dry, the next pass is planned during a round, beside the tail still in flight, so the
// pool stays full from pass to pass (render_loop.cpp: runPass). Between rounds it polls
// the stop conditions; samples still in flight at a stop never reach the film.
#pragma once
#include <chrono>
#include <cstdint>
#include <deque>
#include <optional>
#include <vector>

#include "device_scene.h"
#include "film/film.h"
#include "ocl/buffer.h"
#include "ocl/kernel.h"
#include "pass_planning.h"
#include "progress.h"
#include "ray_pool.h"
#include "refill.h"
#include "renderer.h"
#include "sample_ring.h"
#include "shaders/shader_set.h"
#include "texture_reshade.h"
#include "treelet_trace.h"

namespace rd {

// What the rounds launch on and write to: the frame's device objects, made by
// Renderer::render before the first pass.
struct FrameDevice {
    const ClContext& ctx;
    const Scene& scene;
    const Features& f;
    const ShadingSetup& shading;
    const DeviceScene& ds;
    RayPool& rp;
    RenderKernels& k;
    TreeletTracer* treelets;  // null: the resident kernels trace
    const TraceScene& traceScene;
    const ShadowSurfaces& shadowSurfaces;
    TextureSet& textures;
    TextureReshade& reshade;
    Profiler& prof;
    SampleRing& ring;
    DeviceBuffer<PixelAccum>& filmBuf;
    DeviceBuffer<AovAccum>& aovBuf;
    DeviceBuffer<float>& shaderAovBuf;
    DeviceBuffer<uint32_t>& numerics;  // RT_NUM_* counters, then a flag per archive
};

// What bounds the passes: the pool, the budgets, the samples asked for.
struct FrameLimits {
    size_t pool = 0;         // the ray pool's capacity
    double timeBudget = 0;   // seconds; 0: none
    double errorTarget = 0;  // the film's relative error; 0: none
    bool overlapPasses =
        false;  // a pass may follow the first (RenderSettings::overlapPasses)
    double plannedSamples = 1;  // the film's pixels times their most samples (progress)
};

class RenderLoop {
public:
    using Clock = std::chrono::steady_clock;
    RenderLoop(const FrameDevice& dev, const RenderSettings& settings,
               const FrameLimits& limits, PassPlanning& planning, SamplePlanner& planner,
               RenderStats& st, Clock::time_point t0);

    // Pass after pass, the first from `firstJobs` with its refill staged, until the plan
    // is done, the error target met or a stop (time budget, signal, an archive to load);
    // sets st.stopReason and, at a stop, the samples it left in flight.
    void run(std::deque<PlannedJob> firstJobs, RefillStage firstRefill,
             double firstPlanMs);

private:
    bool runPass(std::deque<PlannedJob> pending);
    std::deque<PlannedJob> planPass(const std::deque<PlannedJob>& pending);
    bool stopNow();
    void capRound();
    void traceRound();
    void shadeRuns(const std::vector<uint32_t>& counts,
                   const std::vector<uint32_t>& offsets,
                   const DeviceBuffer<uint32_t>& sorted, DeviceBuffer<uint32_t>& retry);
    void finishRound(std::deque<PlannedJob>& pending, cl_uint traced);
    void compactBehind(cl_uint traced, cl_uint base);
    void takeFromSpill();
    void retired(std::deque<PlannedJob>& pending, size_t window);
    bool archiveReached();

    FrameDevice m_dev;
    const RenderSettings& m_settings;
    FrameLimits m_limits;
    PassPlanning& m_planning;
    SamplePlanner& m_planner;
    RenderStats& m_st;
    Clock::time_point m_t0;
    Progress m_progress;
    Refill m_refill;
    const uint32_t m_lights;       // shadow slots a ray (f.shadowSlots())
    const cl_uint m_shaderCount;   // compiled surface shaders
    const size_t m_spillCapacity;  // RayPool::spillCapacity
    const bool m_spawns;           // else a round leaves no ray behind

    // The rays in the pool now, and on the spill stack. Refill tops the pool up to
    // m_roundCap: the whole pool, but under a time budget no more than the device traces
    // in a quarter second, and less near the budget's end (the samples in flight at a
    // stop are lost). Without one, rounds never follow the clock: the passes are planned
    // at the same rounds, and the image is the same, however fast the device runs (a
    // first round that waits on the kernels' JIT had capped the rest at a few thousand
    // rays).
    cl_uint m_n = 0;
    size_t m_roundCap = 0;
    double m_raysPerSec = 0;
    size_t m_spillTop = 0;
    std::vector<uint32_t> m_keyOffsets;
    uint64_t m_nonfiniteRetired =
        0;  // samples the film left out: a later pass replaces them
    uint32_t m_retireLaunches = 0;      // its parity picks retire_samples' progress half
    uint32_t m_prog[3] = {0u, 0u, 0u};  // oldest in flight, aborted, NaN/Inf
    std::vector<uint32_t> m_live;  // close_round's live rays per group of traced rays
    uint32_t m_fitted[3] = {0u, 0u,
                            0u};  // fit_refill's: jobs, their samples, rays spawned
    bool m_eyeQueued = false;     // the next round's eye rays are queued (pipelined)
};

}  // namespace rd
