// pass_planning.h: the planning stage of the render loop. Each adaptive pass is planned
// from the film as the retired samples left it, and the film's error is estimated on the
// way: for --stats' error-against-time series (at an interval), for an error target or a
// time budget (each pass), and for the Sobol sampler's spread ratio, which loosens the
// planner's pixel error. None of what it decides depends on the clock unless a time
// budget does: a render's image is the same however fast its device runs.
#pragma once

#include <chrono>
#include <cstdint>
#include <deque>
#include <functional>
#include <optional>
#include <vector>

#include "film/film.h"
#include "ocl/buffer.h"
#include "ocl/kernel.h"
#include "renderer.h"
#include "sample_ring.h"
#include "sampling.h"

namespace rd {

// What steers the planning.
struct PassTargets {
    float pixelError = 0.01f;     // the scene's per-pixel error
    double errorTarget = 0;       // the film's relative error to stop at; 0: none
    double timeBudget = 0;        // seconds; 0: none
    bool sobol = false;           // the Sobol sampler (its error from two replicates)
    double errorSeriesSec = 0.5;  // RenderSettings::errorSeriesSec
    uint32_t maxJob = 1;          // the most samples a pixel job takes
    bool openEnded() const { return errorTarget > 0 || timeBudget > 0; }
};

class PassPlanning {
public:
    using Clock = std::chrono::steady_clock;
    // `planner` is set up elsewhere (the first pass is planned while the scene is built)
    // before any pass is planned here; `raysSoFar` gives the series' ray counts.
    PassPlanning(const PassTargets& targets, Film& film,
                 DeviceBuffer<PixelAccum>& filmBuf, std::optional<SamplePlanner>& planner,
                 const SampleRing& ring, Profiler& prof, RenderStats& st,
                 Clock::time_point t0, std::function<uint64_t()> raysSoFar);

    // A point of the error series when its interval has passed, or now with `force`;
    // `filmSynced`: the film is read already.
    void sampleError(bool force, bool filmSynced = false) {
        sample(force, filmSynced, false);
    }
    // The film as the retired samples left it, and its error estimate when an error
    // target or a time budget steers the planning. Returns whether the target is met.
    bool readFilm();
    // The next pass, planned from the film (read by readFilm) and cut into pixel jobs.
    // Pixels with samples in flight or queued in `pending` are set aside: their film
    // entries are partial (they wait a pass).
    std::deque<PlannedJob> planPass(const std::deque<PlannedJob>& pending);

private:
    void sample(bool force, bool filmSynced, bool planning);

    PassTargets m_targets;
    Film& m_film;
    DeviceBuffer<PixelAccum>& m_filmBuf;
    std::optional<SamplePlanner>& m_planner;
    const SampleRing& m_ring;
    Profiler& m_prof;
    RenderStats& m_st;
    Clock::time_point m_t0;
    std::function<uint64_t()> m_raysSoFar;
    double m_lastSample = 0;  // the series' last point (s)
    // How far the samples' spread, from which the planner takes each pixel's error,
    // overstates the error under the Sobol sampler (FilmError::spreadOverstates): the
    // planner's pixel error is loosened by as much. Taken as the planner reads the film,
    // at points the render's progress sets and never the clock, or an image would depend
    // on its timing (Sampling.AdaptiveImageDoesNotDependOnTheErrorSeries): each pass
    // under an error target or a time budget (which estimate the error there anyway),
    // else when the retired samples have doubled since it was last taken or since the
    // first plan (an estimate each pass cost SPD tetra at 9 samples a pixel 20 ms of its
    // 170; it has no such doubling). Rounded down to quarter octaves, as a tighter pixel
    // error makes the planner test every pixel again.
    double m_spreadOverstates = 1.0;
    uint64_t m_overstatesTakenAt = 0;  // retired samples then; 0: no plan yet
    std::vector<uint8_t> m_busy;  // pixels with samples in flight when a pass is planned
};

}  // namespace rd
