// refill.h: the refill stage (AR250: new eye rays whenever the pool has room, so eye and
// secondary rays share rounds). Whole pixel jobs from the front of a pass's queue go into
// the free end of the ray pool, in three steps so that the host's part overlaps the
// device's round: prepare(), before the round's wait, writes the records and (pixel,
// index) pairs of the jobs that surely fit (a round's worth, the slot ring as it is)
// without waiting; commit() launches generate_eye for the prefix that fits beside the
// rays the pool holds, once the compaction has counted them. Or, queued before the
// round's wait so that the device works on while the host wakes up, fit() has the device
// count the rays the round spawned and find the prefix that fits beside them, and
// commitFitted() launches generate_eye for it at the pool's front. book() enters those jobs
// in the ring's books once the round's kernels are queued (thousands of one-sample jobs
// a round, booked while the device traces).
#pragma once
#include <deque>
#include <vector>

#include "cl/include/film.h"
#include "cl/include/scene_types.h"
#include "ocl/buffer.h"
#include "ocl/kernel.h"
#include "ray_pool.h"
#include "sample_ring.h"

namespace rd {

// The host's part of a refill: the records and (pixel, sample index) pairs of the jobs at
// the queue's front that surely fit (a round's worth, the slot ring as it is).
struct RefillStage {
    std::vector<uint32_t> newSamples;  // (pixel, sample index) pairs
    std::vector<PixelJob> records;
    std::vector<uint32_t> ends;  // ends[j]: samples in jobs 0..j
    bool ringBound = false;      // the slot ring, not the round, cut it
};
// Fills `out` (its vectors reused) for the ring as it is. Touches neither the device nor
// the ring, so the first pass's stage is made on the planning thread while the program
// builds (32k one-sample jobs: 0.5 ms the device would otherwise wait through).
void stageRefill(const SampleRing& ring, const std::deque<PlannedJob>& pending,
                 size_t roundCap, RefillStage& out);

class Refill {
public:
    Refill(SampleRing& ring, RayPool& pool, Kernel& generateEye, Kernel& fitRefill,
           const DeviceBuffer<Camera>& camera)
        : m_ring(ring),
          m_pool(pool),
          m_generateEye(generateEye),
          m_fitRefill(fitRefill),
          m_camera(camera) {}
    // The front of the queue changed (a new pass, jobs issued again): prepare anew.
    void invalidate() { m_valid = false; }
    void prepare(const std::deque<PlannedJob>& pending, size_t roundCap);
    // The same with a stage made beforehand for the ring as it is now.
    void adopt(RefillStage&& stage);
    // Launches generate_eye for the prepared jobs that fit beside `reserved` rays within
    // roundCap (with none reserved, one job whatever the cap); returns the eye rays added
    // at [offset, offset + added). The rays after n held: offset = reserved = n.
    cl_uint commit(const std::deque<PlannedJob>& pending, cl_uint offset, size_t reserved,
                   size_t roundCap);
    // Queues fit_refill over the prepared jobs beside the rays close_round counted in
    // `groups` groups and those the pool takes back from the spill stack's `spillTop`
    // (RayPool::refillFit); returns false, queuing nothing, when no job is prepared.
    // commitFitted() then queues their generate_eye at the pool's front and books every
    // prepared job while the device works; once the host has read refillFit,
    // bookFitted takes back those that did not fit (usually none).
    bool fit(size_t groups, size_t spillTop, size_t roundCap);
    void commitFitted(std::deque<PlannedJob>& pending);
    // The jobs commitFitted() launched were cut by the slot ring (as it was before the
    // round's retire): more may fit now.
    bool fittedRingBound() const { return m_fittedRingBound; }
    void bookFitted(std::deque<PlannedJob>& pending, uint32_t jobs);
    void book(std::deque<PlannedJob>& pending);

private:
    SampleRing& m_ring;
    RayPool& m_pool;
    Kernel& m_generateEye;
    Kernel& m_fitRefill;
    const DeviceBuffer<Camera>& m_camera;
    // What prepare() uploads without waiting must stay put until the device has run the
    // write. A round may prepare twice (at its start and before its wait), and the wait
    // covers only what was queued before the round's reads: the last prepare's write is
    // run by the next round's wait. Three staging sets, used in turn.
    static constexpr int kStagingSets = 3;
    RefillStage m_staging[kStagingSets];
    int m_set = 0;
    bool m_valid = false;
    size_t m_toBook = 0;  // jobs launched, not yet in the ring's books
    bool m_fittedRingBound = false;
    void upload();
    // generate_eye over `items` work-items for `count` samples (~0u: fit_refill's)
    void launchEye(cl_uint items, cl_uint count, cl_uint offset);
};

}  // namespace rd
