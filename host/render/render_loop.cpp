// render_loop.cpp: the passes (render_loop.h). Each pass's jobs stream through the pool a
// round at a time (render_round.cpp); the next pass is planned beside the last one's
// tail; between rounds the stop conditions are polled.
#include "render_loop.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "cl/include/numerics_slots.h"
#include "stop.h"

namespace rd {

namespace {

double secondsSince(RenderLoop::Clock::time_point t0) {
    return std::chrono::duration<double>(RenderLoop::Clock::now() - t0).count();
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

// the first archive flag after the counters
constexpr size_t kProceduralFlags = RT_NUM_PROCEDURAL_BASE;

const char* signalName(int sig) {
    return sig == 2 ? "SIGINT" : sig == 15 ? "SIGTERM" : "signal";
}

}  // namespace

RenderLoop::RenderLoop(const FrameDevice& dev, const RenderSettings& settings,
                       const FrameLimits& limits, PassPlanning& planning,
                       SamplePlanner& planner, RenderStats& st, Clock::time_point t0)
    : m_dev(dev),
      m_settings(settings),
      m_limits(limits),
      m_planning(planning),
      m_planner(planner),
      m_st(st),
      m_t0(t0),
      m_progress(settings.progress),
      m_refill(dev.ring, dev.rp, dev.k.generateEye, dev.k.fitRefill, dev.ds.cameraBuf),
      m_lights(dev.f.shadowSlots()),
      m_shaderCount(cl_uint(dev.shading.shadeKernels.size())),
      m_spillCapacity(RayPool::spillCapacity(limits.pool, size_t(dev.f.spawnSlots()),
                                             dev.f.shaderShadows)),
      m_spawns(dev.f.spawns()),
      m_roundCap(limits.pool) {}

void RenderLoop::run(std::deque<PlannedJob> firstJobs, RefillStage firstRefill,
                     double firstPlanMs) {
    m_dev.prof
        .markHostWait();  // the set-up: the device had nothing to do before the loop
    bool first = true;
    for (;;) {
        std::deque<PlannedJob> jobs;
        if (first) {
            jobs = std::move(firstJobs);
            m_refill.adopt(std::move(firstRefill));
            m_st.planMs += firstPlanMs;
            first = false;
        } else {
            jobs = planPass({});
        }
        if (jobs.empty()) {
            m_st.stopReason = "quality";
            break;
        }
        if (!runPass(std::move(jobs))) {
            m_st.abortedSamples = m_dev.ring.samplesInFlight();  // never reach the film
            break;
        }
        if (m_planner.firstPassIsFinal() && m_nonfiniteRetired == 0 &&
            m_limits.errorTarget <= 0) {
            m_st.stopReason =
                "quality";  // every pixel has all its samples: nothing to plan
            break;
        }
        if (m_planning.readFilm()) {
            m_st.stopReason = "error target";
            break;
        }
    }
    m_progress.finish();
}

std::deque<PlannedJob> RenderLoop::planPass(const std::deque<PlannedJob>& pending) {
    std::deque<PlannedJob> jobs = m_planning.planPass(pending);
    m_refill.invalidate();  // a new queue
    return jobs;
}

bool RenderLoop::stopNow() {
    if (int sig = stopSignal()) {
        m_st.stopReason = signalName(sig);
        return true;
    }
    // The first round always completes, so a budget smaller than the set-up time still
    // yields an image (at the cost of overrunning it by one short round).
    if (m_limits.timeBudget > 0 && m_st.iterations > 0 &&
        secondsSince(m_t0) >= m_limits.timeBudget) {
        m_st.stopReason = "time budget";
        return true;
    }
    return false;
}

// Near the end of a time budget, a round takes only what the device traces before it.
void RenderLoop::capRound() {
    if (m_limits.timeBudget > 0 && m_raysPerSec > 0)
        m_roundCap = std::clamp<size_t>(
            size_t(m_raysPerSec *
                   std::max(0.0, m_limits.timeBudget - secondsSince(m_t0)) * 0.9),
            std::min<size_t>(256, m_roundCap), m_roundCap);
}

// A ray reached a deferred archive's bound: the render stops to load it first.
bool RenderLoop::archiveReached() {
    m_dev.prof.markHostWait();
    std::vector<uint32_t> flags = m_dev.numerics.download();
    const auto& procedurals = m_dev.scene.procedurals;
    for (size_t a = 0; a < procedurals.size(); ++a)
        if (flags[kProceduralFlags + a])
            m_st.proceduralsReached.push_back(procedurals[a].key);
    if (m_st.proceduralsReached.empty()) return false;
    m_st.stopReason = "archives to load";
    return true;
}

// The pass's jobs stream through the pool: refill, trace, compact, retire, until every
// job has retired (the caller has staged its first refill or invalidated the last
// pass's). With overlapPasses, once the next round takes all that is left (the rays and
// the queued jobs: kOverlapFill), the next pass is planned from the film as the round
// left it, during the next round's kernels (none of which writes the film before that
// round's retire), and streams on beside the tail: its eye rays keep the pool full.
// Returns false when a stop ends it early.
bool RenderLoop::runPass(std::deque<PlannedJob> pending) {
    const size_t pool = m_limits.pool;
    SampleRing& ring = m_dev.ring;
    bool overlap = m_limits.overlapPasses, planDue = false;
    while (!pending.empty() || ring.inFlight() > 0) {
        if (stopNow()) return false;
        if (!m_eyeQueued) {
            capRound();
            const cl_uint added = m_refill.commit(pending, m_n, m_n, m_roundCap);
            m_n += added;
            m_st.eyeRays += added;
        }
        m_eyeQueued = false;
        if (m_n == 0 && m_spillTop == 0 && ring.inFlight() == 0)
            throw std::runtime_error(
                "internal error: a pixel job larger than the ray pool");
        const auto tRound = Clock::now();
        double planSec = 0;  // of the round's time: planning the next pass
        const cl_uint traced = m_n;
        if (m_n > 0) {
            traceRound();
            if (m_st.poolFillSeries.empty() ||
                secondsSince(m_t0) - m_st.poolFillSeries.back().seconds >= 0.05)
                m_st.poolFillSeries.push_back(
                    {secondsSince(m_t0), double(m_n) / double(pool)});
        }
        m_refill.book(pending);
        if (planDue) {
            planDue = false;
            const auto tPlan = Clock::now();
            std::deque<PlannedJob> next = planPass(pending);
            planSec = secondsSince(tPlan);
            // the device may have run out of queued kernels meanwhile: the host's time
            m_dev.prof.markHostWait();
            // nothing to add beside the tail: drain it, then plan with every pixel known
            overlap = !next.empty();
            m_st.overlappedPasses += overlap;
            if (pending.empty())
                pending = std::move(next);
            else
                pending.insert(pending.end(), next.begin(), next.end());
        }
        const size_t inFlightBefore = ring.inFlight();
        finishRound(pending, traced);  // its read waits for the round: time it here
        // No ray anywhere yet a job still in flight would loop for ever: a sample's count
        // of rays went wrong. Never hang: stop with a clear error.
        if (traced == 0 && m_spillTop == 0 && ring.inFlight() == inFlightBefore &&
            inFlightBefore > 0)
            throw std::runtime_error(
                "internal error: samples in flight with no ray left");
        // (a round of a few rays is its fixed costs: no measure of the rate)
        if (const double dt = secondsSince(tRound) - planSec;
            dt > 0 && (traced >= pool / 8 || (traced > 0 && m_raysPerSec == 0))) {
            m_raysPerSec = double(traced) / dt;
            if (m_limits.timeBudget > 0)
                m_roundCap = std::clamp<size_t>(size_t(m_raysPerSec * 0.25),
                                                std::min<size_t>(1024, pool), pool);
        }
        ++m_st.iterations;
        if (m_dev.f.procedurals && archiveReached()) return false;
        m_planning.sampleError(false);
        const double fraction =
            m_limits.timeBudget > 0 ? secondsSince(m_t0) / m_limits.timeBudget
            : m_limits.errorTarget > 0 && m_st.estimatedError > 0
                ? std::min(1.0, std::log(1.0 / m_st.estimatedError) /
                                    std::log(1.0 / m_limits.errorTarget))
                : double(m_st.retiredSamples) / m_limits.plannedSamples;
        m_progress.update(fraction, secondsSince(m_t0), m_st.eyeRays,
                          m_st.estimatedError);
        const size_t fill = size_t(kOverlapFill * double(m_roundCap));
        if (overlap && (ring.inFlight() > 0 || !pending.empty()) && m_spillTop == 0 &&
            m_n <= fill && queueWithin(pending, fill - m_n)) {
            planDue = !m_planning.readFilm();  // the error target met: drain, then stop
            overlap = planDue;
        }
    }
    return true;
}

}  // namespace rd
