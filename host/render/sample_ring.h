// sample_ring.h: the host's book of sample slots and pixel jobs. RenderDrive kept each eye
// sample's total on the chip until its last ray came back; here a sample owns a slot in a
// ring of slots on the device, and the samples of one pixel in one pass (a pixel job)
// take consecutive slots. Jobs retire on the device in any order; the host frees the
// slots of the retired prefix (the oldest jobs first), so a late job holds back only the
// slots after it, and the ring is sized well above the ray pool to absorb that.
#pragma once
#include <cstddef>
#include <cstdint>
#include <deque>
#include <vector>

#include "cl/include/film.h"
#include "sampling.h"

namespace rd {

// A job the host plans: samples [firstSample, + count) of `pixel`, and whether it was
// issued before (aborted) and so retires with what it has next time.
struct PlannedJob {
    uint32_t pixel = 0, firstSample = 0, count = 0;
    bool lastTry = false;
    bool exclusive = false;  // the pixel's only job in its pass (RT_JOB_EXCLUSIVE)
};

// Cuts a pass's requests into jobs of at most `maxJob` samples, in the pass's order, and
// marks the jobs that are their pixel's only one in the pass (pixels < pixelCount).
// `eachPixelOnce`: no pixel has two requests in the pass (an adaptive pass's), so a
// request of at most maxJob samples is its pixel's only job, and no table of the pixels'
// jobs is needed (262 KB cleared a 512x512 pass).
std::deque<PlannedJob> planJobs(const std::vector<PixelRequest>& pass, uint32_t maxJob,
                                size_t pixelCount, bool eachPixelOnce = false);

class SampleRing {
public:
    explicit SampleRing(size_t slots) : m_slots(slots), m_jobs(slots), m_jobEnd(slots) {}
    size_t slotCapacity() const { return m_slots; }
    size_t jobCapacity() const { return m_slots; }  // a job takes at least one slot
    // Whether a job of `count` samples fits after `jobsAhead` jobs of `slotsAhead` samples
    // not pushed yet, and the record push() will give it then.
    bool fitsAhead(size_t slotsAhead, size_t jobsAhead, uint32_t count) const {
        return samplesInFlight() + slotsAhead + count <= m_slots &&
               m_inFlight + jobsAhead < jobCapacity();
    }
    PixelJob recordAhead(size_t slotsAhead, const PlannedJob& job) const;
    // Records the job and returns its device record (state, first slot filled in).
    PixelJob push(const PlannedJob& job);
    bool fits(uint32_t count) const { return fitsAhead(0, 0, count); }
    size_t nextSlot() const { return size_t(m_pushed % m_slots); }
    size_t nextJobPosition() const { return (m_frontPos + m_inFlight) % jobCapacity(); }
    // The jobs in flight: ring positions [frontPosition(), + inFlight()).
    size_t frontPosition() const { return m_frontPos; }
    size_t inFlight() const { return m_inFlight; }
    const PlannedJob& at(size_t k) const { return m_jobs[(m_frontPos + k) % jobCapacity()]; }
    // The samples of the oldest `n` jobs in flight (n clipped to inFlight()).
    uint64_t samplesInFront(size_t n) const;
    // The oldest `n` jobs retired (or were aborted): their slots are free again. O(1): a
    // round retires thousands of one-sample jobs.
    void popFront(size_t n);
    // The newest `n` jobs taken back, never issued (their slots free again): pushed
    // before the device said how many of them fit.
    void popBack(size_t n);
    uint64_t samplesInFlight() const { return m_pushed - m_popped; }
    // Marks busy[pixel] for every job in flight (jobs retired behind an older one still
    // in flight included: the host has not freed them yet).
    void markPixelsInFlight(std::vector<uint8_t>& busy) const;

private:
    size_t m_slots;
    std::vector<PlannedJob> m_jobs;  // by ring position
    std::vector<uint64_t> m_jobEnd;  // by ring position: samples pushed up to that job's end
    uint64_t m_pushed = 0, m_popped = 0;  // samples ever pushed, ever freed
    size_t m_frontPos = 0, m_inFlight = 0;
};

}  // namespace rd
