// sample_ring.cpp: pixel jobs cut from a pass, and the slot and job rings (sample_ring.h).
#include "sample_ring.h"

#include <algorithm>

namespace rd {

std::deque<PlannedJob> planJobs(const std::vector<PixelRequest>& pass, uint32_t maxJob,
                                size_t pixelCount, bool eachPixelOnce) {
    std::deque<PlannedJob> jobs;
    maxJob = std::max(1u, maxJob);
    std::vector<uint8_t> jobsOfPixel(eachPixelOnce ? 0 : pixelCount, 0);  // saturating at 2
    if (!eachPixelOnce)
        for (const PixelRequest& r : pass)
            if (r.pixel < pixelCount) {
                const uint32_t n = (r.count + maxJob - 1) / maxJob;
                jobsOfPixel[r.pixel] = uint8_t(std::min<uint32_t>(2, jobsOfPixel[r.pixel] + n));
            }
    for (const PixelRequest& r : pass) {
        // (each pixel once: a request of at most maxJob samples is its pixel's one job)
        const bool alone = r.pixel < pixelCount &&
                           (eachPixelOnce ? r.count <= maxJob : jobsOfPixel[r.pixel] == 1);
        for (uint32_t done = 0; done < r.count;) {
            const uint32_t take = std::min(maxJob, r.count - done);
            jobs.push_back({r.pixel, r.first + done, take, false, alone});
            done += take;
        }
    }
    return jobs;
}

PixelJob SampleRing::recordAhead(size_t slotsAhead, const PlannedJob& job) const {
    return PixelJob{job.pixel, uint32_t((m_pushed + slotsAhead) % m_slots), job.count,
                    (job.lastTry ? RT_JOB_LAST_TRY : RT_JOB_IN_FLIGHT) |
                        (job.exclusive ? RT_JOB_EXCLUSIVE : 0u) |
                        (job.firstSample & 1u ? RT_JOB_ODD_FIRST : 0u)};
}

PixelJob SampleRing::push(const PlannedJob& job) {
    const PixelJob rec = recordAhead(0, job);
    const size_t pos = nextJobPosition();
    m_jobs[pos] = job;
    m_pushed += job.count;
    m_jobEnd[pos] = m_pushed;
    ++m_inFlight;
    return rec;
}

uint64_t SampleRing::samplesInFront(size_t n) const {
    n = std::min(n, m_inFlight);
    return n == 0 ? 0 : m_jobEnd[(m_frontPos + n - 1) % jobCapacity()] - m_popped;
}

void SampleRing::popFront(size_t n) {
    n = std::min(n, m_inFlight);
    m_popped += samplesInFront(n);
    m_frontPos = (m_frontPos + n) % jobCapacity();
    m_inFlight -= n;
}

void SampleRing::popBack(size_t n) {
    n = std::min(n, m_inFlight);
    m_inFlight -= n;
    m_pushed = m_inFlight == 0 ? m_popped : m_jobEnd[(m_frontPos + m_inFlight - 1) % jobCapacity()];
}

void SampleRing::markPixelsInFlight(std::vector<uint8_t>& busy) const {
    for (size_t k = 0; k < m_inFlight; ++k)
        if (const uint32_t p = at(k).pixel; p < busy.size()) busy[p] = 1;
}

}  // namespace rd
