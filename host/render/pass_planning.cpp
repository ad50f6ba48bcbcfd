// pass_planning.cpp: the adaptive passes planned from the film, and its error estimates.
#include "pass_planning.h"

#include <algorithm>

#include "film/film_error.h"

namespace rd {
namespace {
double secondsSince(PassPlanning::Clock::time_point t0) {
    return std::chrono::duration<double>(PassPlanning::Clock::now() - t0).count();
}
}  // namespace

PassPlanning::PassPlanning(const PassTargets& targets, Film& film,
                           DeviceBuffer<PixelAccum>& filmBuf,
                           std::optional<SamplePlanner>& planner, const SampleRing& ring,
                           Profiler& prof, RenderStats& st, Clock::time_point t0,
                           std::function<uint64_t()> raysSoFar)
    : m_targets(targets),
      m_film(film),
      m_filmBuf(filmBuf),
      m_planner(planner),
      m_ring(ring),
      m_prof(prof),
      m_st(st),
      m_t0(t0),
      m_raysSoFar(std::move(raysSoFar)) {}

void PassPlanning::sample(bool force, bool filmSynced, bool planning) {
    const double now = secondsSince(m_t0);
    const bool seriesDue = force || now - m_lastSample >= m_targets.errorSeriesSec;
    // (the first plan sets the baseline: its pixels have the first pass's two samples,
    // of which the spread and the replicates give the same number)
    if (planning && m_overstatesTakenAt == 0)
        m_overstatesTakenAt = std::max<uint64_t>(1, m_st.retiredSamples);
    const bool openEnded = m_targets.openEnded();
    const bool overstatesDue =
        planning && m_targets.sobol &&
        (openEnded || m_st.retiredSamples >= 2 * m_overstatesTakenAt);
    if (!seriesDue && !overstatesDue) return;
    if (!filmSynced) {
        m_prof.markHostWait();
        m_filmBuf.syncToHost();
    }
    const FilmError e = seriesDue ? estimateFilmErrors(m_film.pixels) : FilmError{};
    if (overstatesDue) {
        // Open-ended, from the estimate taken each pass; else from one of every seven
        // of the film's batches whether or not the series is due (0.2 ms, not 1.2, on
        // SPD tetra's 262k pixels; seven, so that they fall on other columns of each
        // row).
        const FilmError r = openEnded ? e : estimateFilmErrors(m_film.pixels, 7);
        if (r.replicates > 0) {
            m_spreadOverstates =
                roundDownOnOctaveGrid(r.spreadOverstates(m_targets.sobol), 4.0);
            m_overstatesTakenAt = std::max<uint64_t>(1, m_st.retiredSamples);
        }
    }
    if (!seriesDue) return;
    m_lastSample = now;
    m_st.estimatedError = e.of(m_targets.sobol);
    m_prof.collect();
    m_st.errorVsTime.push_back({now, m_raysSoFar(), m_st.estimatedError});
}

bool PassPlanning::readFilm() {
    const auto tFilm = Clock::now();
    m_prof.markHostWait();
    m_filmBuf.syncToHost();
    sample(m_targets.openEnded(), /*filmSynced=*/true, /*planning=*/true);
    m_st.planMs += secondsSince(tFilm) * 1e3;
    const double target = m_targets.errorTarget;
    return target > 0 && m_st.estimatedError >= 0 && m_st.estimatedError <= target;
}

std::deque<PlannedJob> PassPlanning::planPass(const std::deque<PlannedJob>& pending) {
    float pixelError = m_targets.pixelError;
    if (m_targets.errorTarget > 0)
        pixelError = float(m_targets.errorTarget);
    else if (m_targets.timeBudget > 0 && m_st.estimatedError > 0)
        pixelError = float(0.5 * m_st.estimatedError);  // refine the worse half
    const auto tPlan = Clock::now();
    const size_t pixels = m_film.pixels.size();
    m_busy.assign(m_ring.inFlight() > 0 || !pending.empty() ? pixels : 0, 0);
    m_ring.markPixelsInFlight(m_busy);
    for (const PlannedJob& j : pending) m_busy[j.pixel] = 1;
    std::deque<PlannedJob> jobs =
        planJobs(m_planner->nextPass(m_film.pixels,
                                     float(pixelError * m_spreadOverstates), m_busy),
                 m_targets.maxJob, pixels, /*eachPixelOnce=*/true);
    m_st.planMs += secondsSince(tPlan) * 1e3;
    return jobs;
}

}  // namespace rd
