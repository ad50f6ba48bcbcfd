// refill.cpp: the refill stage's prepare, commit and book steps (refill.h).
#include "refill.h"

#include <algorithm>

namespace rd {

void Refill::prepare(const std::deque<PlannedJob>& pending, size_t roundCap) {
    m_set ^= 1;
    std::vector<uint32_t>& newSamples = m_staging[m_set].newSamples;
    std::vector<PixelJob>& records = m_staging[m_set].records;
    newSamples.clear();
    records.clear();
    m_ends.clear();
    m_ringBound = false;
    size_t ahead = 0;
    for (const PlannedJob& j : pending) {
        if (ahead + j.count > roundCap && !records.empty()) break;
        if (!m_ring.fitsAhead(ahead, records.size(), j.count)) {
            m_ringBound = true;
            break;
        }
        records.push_back(m_ring.recordAhead(ahead, j));
        for (uint32_t c = 0; c < j.count; ++c) {
            newSamples.push_back(j.pixel);
            newSamples.push_back(j.firstSample + c);
        }
        ahead += j.count;
        m_ends.push_back(uint32_t(ahead));
    }
    m_valid = true;
    if (records.empty()) return;
    const size_t jobPos = m_ring.nextJobPosition();
    const size_t wrap = std::min(records.size(), m_ring.jobCapacity() - jobPos);
    m_pool.jobs.uploadAsync(jobPos, records.data(), wrap);
    if (wrap < records.size())
        m_pool.jobs.uploadAsync(0, records.data() + wrap, records.size() - wrap);
    m_pool.newSample.uploadAsync(0, newSamples.data(), newSamples.size());
}

cl_uint Refill::commit(const std::deque<PlannedJob>& pending, cl_uint n, size_t roundCap) {
    if (!m_valid || m_ringBound) prepare(pending, roundCap);  // (slots freed since)
    m_valid = false;
    size_t take = 0;
    while (take < m_ends.size() && (n + m_ends[take] <= roundCap || (n == 0 && take == 0)))
        ++take;
    if (take == 0) return 0;
    const cl_uint add = m_ends[take - 1];
    RayPool& rp = m_pool;
    m_generateEye.launch(add, m_camera, add, n, cl_uint(m_ring.nextSlot()),
                         cl_uint(m_ring.slotCapacity()), rp.newSample, rp.samplePixel,
                         rp.sampleIndex, rp.slotRays, rp.slotAbort, rp.origin, rp.direction,
                         rp.weight, rp.state, rp.sample, rp.totals, rp.aov, rp.sampleTime);
    m_toBook = take;
    return add;
}

void Refill::book(std::deque<PlannedJob>& pending) {
    for (; m_toBook > 0; --m_toBook) {
        m_ring.push(pending.front());
        pending.pop_front();
    }
}

}  // namespace rd
