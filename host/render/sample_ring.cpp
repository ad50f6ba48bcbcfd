// sample_ring.cpp: pixel jobs cut from a pass, and the slot and job rings (sample_ring.h).
#include "sample_ring.h"

#include <algorithm>

namespace rd {

std::deque<PlannedJob> planJobs(const std::vector<PixelRequest>& pass, uint32_t maxJob) {
    std::deque<PlannedJob> jobs;
    maxJob = std::max(1u, maxJob);
    for (const PixelRequest& r : pass)
        for (uint32_t done = 0; done < r.count;) {
            uint32_t take = std::min(maxJob, r.count - done);
            jobs.push_back({r.pixel, r.first + done, take, false});
            done += take;
        }
    return jobs;
}

PixelJob SampleRing::recordAhead(size_t slotsAhead, const PlannedJob& job) const {
    return PixelJob{job.pixel, uint32_t((m_slotHead + slotsAhead) % m_slots), job.count,
                    job.lastTry ? RT_JOB_LAST_TRY : RT_JOB_IN_FLIGHT};
}

PixelJob SampleRing::push(const PlannedJob& job) {
    const PixelJob rec = recordAhead(0, job);
    m_slotHead = (m_slotHead + job.count) % m_slots;
    m_slotsUsed += job.count;
    m_jobs.push_back(job);
    return rec;
}

void SampleRing::popFront(size_t n) {
    for (size_t k = 0; k < n && !m_jobs.empty(); ++k) {
        m_slotsUsed -= m_jobs.front().count;
        m_jobs.pop_front();
        m_frontPos = (m_frontPos + 1) % jobCapacity();
    }
}

}  // namespace rd
