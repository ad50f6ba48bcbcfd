// refill.cpp: the refill stage's prepare, commit and book steps (refill.h).
#include "refill.h"

#include <algorithm>

namespace rd {

void stageRefill(const SampleRing& ring, const std::deque<PlannedJob>& pending,
                 size_t roundCap, RefillStage& out) {
    out.newSamples.clear();
    out.records.clear();
    out.ends.clear();
    out.ringBound = false;
    size_t ahead = 0;
    for (const PlannedJob& j : pending) {
        if (ahead + j.count > roundCap && !out.records.empty()) break;
        if (!ring.fitsAhead(ahead, out.records.size(), j.count)) {
            out.ringBound = true;
            break;
        }
        out.records.push_back(ring.recordAhead(ahead, j));
        for (uint32_t c = 0; c < j.count; ++c) {
            out.newSamples.push_back(j.pixel);
            out.newSamples.push_back(j.firstSample + c);
        }
        ahead += j.count;
        out.ends.push_back(uint32_t(ahead));
    }
}

void Refill::prepare(const std::deque<PlannedJob>& pending, size_t roundCap) {
    m_set = (m_set + 1) % kStagingSets;
    stageRefill(m_ring, pending, roundCap, m_staging[m_set]);
    upload();
}

void Refill::adopt(RefillStage&& stage) {
    m_set = (m_set + 1) % kStagingSets;
    m_staging[m_set] = std::move(stage);
    upload();
}

void Refill::upload() {
    m_valid = true;
    const std::vector<PixelJob>& records = m_staging[m_set].records;
    if (records.empty()) return;
    const size_t jobPos = m_ring.nextJobPosition();
    const size_t wrap = std::min(records.size(), m_ring.jobCapacity() - jobPos);
    m_pool.jobs.uploadAsync(jobPos, records.data(), wrap);
    if (wrap < records.size())
        m_pool.jobs.uploadAsync(0, records.data() + wrap, records.size() - wrap);
    const std::vector<uint32_t>& newSamples = m_staging[m_set].newSamples;
    m_pool.newSample.uploadAsync(0, newSamples.data(), newSamples.size());
    const std::vector<uint32_t>& ends = m_staging[m_set].ends;
    m_pool.refillEnds.uploadAsync(0, ends.data(), ends.size());
}

cl_uint Refill::commit(const std::deque<PlannedJob>& pending, cl_uint offset, size_t reserved,
                       size_t roundCap) {
    if (!m_valid || m_staging[m_set].ringBound)
        prepare(pending, roundCap);  // (slots freed since)
    m_valid = false;
    const std::vector<uint32_t>& ends = m_staging[m_set].ends;
    size_t take = 0;
    while (take < ends.size() && (reserved + ends[take] <= roundCap || (reserved == 0 && take == 0)))
        ++take;
    if (take == 0) return 0;
    const cl_uint add = ends[take - 1];
    launchEye(add, add, offset);
    m_toBook = take;
    return add;
}

bool Refill::fit(size_t groups, size_t spillTop, size_t roundCap) {
    const std::vector<uint32_t>& ends = m_staging[m_set].ends;
    if (!m_valid || ends.empty()) return false;
    m_fitRefill.launch(RT_COMPACT_GROUP, cl_uint(groups), m_pool.groupLive,
                       cl_uint(m_pool.origin.size()), cl_uint(spillTop), cl_uint(ends.size()), m_pool.refillEnds, cl_uint(roundCap),
                       m_pool.refillFit);
    return true;
}

void Refill::commitFitted(std::deque<PlannedJob>& pending) {
    m_valid = false;
    m_fittedRingBound = m_staging[m_set].ringBound;
    launchEye(m_staging[m_set].ends.back(), ~0u, 0);
    m_toBook = m_staging[m_set].ends.size();
    book(pending);
}

void Refill::bookFitted(std::deque<PlannedJob>& pending, uint32_t jobs) {
    for (size_t k = m_staging[m_set].ends.size(); k > jobs; --k) {
        pending.push_front(m_ring.at(m_ring.inFlight() - 1));
        m_ring.popBack(1);
    }
}

void Refill::launchEye(cl_uint items, cl_uint count, cl_uint offset) {
    RayPool& rp = m_pool;
    m_generateEye.launch(items, m_camera, count, rp.refillFit, offset,
                         cl_uint(m_ring.nextSlot()), cl_uint(m_ring.slotCapacity()),
                         rp.newSample, rp.samplePixel, rp.sampleIndex, rp.slotRays,
                         rp.slotAbort, rp.origin, rp.direction, rp.weight, rp.state, rp.sample,
                         rp.totals, rp.aov, rp.aovValues, rp.sampleTime);
}

void Refill::book(std::deque<PlannedJob>& pending) {
    for (; m_toBook > 0; --m_toBook) {
        m_ring.push(pending.front());
        pending.pop_front();
    }
}

}  // namespace rd
