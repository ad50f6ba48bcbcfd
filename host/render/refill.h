// refill.h: the refill stage (AR250: new eye rays whenever the pool has room, so eye and
// secondary rays share rounds). Whole pixel jobs from the front of a pass's queue go into
// the free end of the ray pool, in three steps so that the host's part overlaps the
// device's round: prepare(), before the round's wait, writes the records and (pixel,
// index) pairs of the jobs that surely fit (a round's worth, the slot ring as it is)
// without waiting; commit(), once the compaction has said how many rays the pool holds,
// launches generate_eye for the prefix that fits beside them; book() enters those jobs
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
    Refill(SampleRing& ring, RayPool& pool, Kernel& generateEye,
           const DeviceBuffer<Camera>& camera)
        : m_ring(ring), m_pool(pool), m_generateEye(generateEye), m_camera(camera) {}
    // The front of the queue changed (a new pass, jobs issued again): prepare anew.
    void invalidate() { m_valid = false; }
    void prepare(const std::deque<PlannedJob>& pending, size_t roundCap);
    // The same with a stage made beforehand for the ring as it is now.
    void adopt(RefillStage&& stage);
    // Launches generate_eye for the prepared jobs that fit beside the pool's n rays
    // within roundCap (an empty pool takes one job whatever the cap); returns the eye
    // rays added at [n, n + added).
    cl_uint commit(const std::deque<PlannedJob>& pending, cl_uint n, size_t roundCap);
    void book(std::deque<PlannedJob>& pending);

private:
    SampleRing& m_ring;
    RayPool& m_pool;
    Kernel& m_generateEye;
    const DeviceBuffer<Camera>& m_camera;
    // What prepare() uploads without waiting must stay put until the device has run the
    // write: the end-of-round wait does. Two staging sets, used in turn, as a round may
    // prepare twice before that wait (at its start and before it).
    RefillStage m_staging[2];
    int m_set = 0;
    bool m_valid = false;
    size_t m_toBook = 0;  // jobs launched, not yet in the ring's books
    void upload();
};

}  // namespace rd
