// sample_ring_test.cpp: pixel jobs cut from a pass, and the host's book of the sample-slot
// and job rings (host/render/sample_ring.h).
#include <gtest/gtest.h>

#include "render/refill.h"
#include "render/sample_ring.h"

using rd::PlannedJob;
using rd::SampleRing;
using rd::RefillStage;

TEST(SampleRing, PassesAreCutIntoJobsOfAtMostMaxSamples) {
    std::vector<rd::PixelRequest> pass = {{7, 0, 3}, {9, 4, 10}};
    auto jobs = rd::planJobs(pass, 4, 100);
    ASSERT_EQ(jobs.size(), 4u);  // 3 | 4 + 4 + 2
    EXPECT_EQ(jobs[0].pixel, 7u);
    EXPECT_EQ(jobs[0].count, 3u);
    EXPECT_EQ(jobs[1].firstSample, 4u);
    EXPECT_EQ(jobs[2].firstSample, 8u);
    EXPECT_EQ(jobs[3].firstSample, 12u);
    EXPECT_EQ(jobs[3].count, 2u);
    EXPECT_EQ(rd::planJobs(pass, 0, 100).size(), 13u) << "a zero limit still makes progress";
}

TEST(SampleRing, SlotsAreConsecutiveAndFreedOldestFirst) {
    SampleRing ring(10);
    EXPECT_TRUE(ring.fits(10));
    EXPECT_FALSE(ring.fits(11));
    PixelJob a = ring.push({1, 0, 6, false});
    PixelJob b = ring.push({2, 0, 3, true});
    EXPECT_EQ(a.first_slot, 0u);
    EXPECT_EQ(a.state, RT_JOB_IN_FLIGHT);
    EXPECT_EQ(b.first_slot, 6u);
    EXPECT_EQ(b.state, RT_JOB_LAST_TRY);
    EXPECT_EQ(ring.samplesInFlight(), 9u);
    EXPECT_FALSE(ring.fits(2));
    ring.popFront(1);  // the oldest job retired: its 6 slots are free again
    EXPECT_EQ(ring.frontPosition(), 1u);
    EXPECT_EQ(ring.inFlight(), 1u);
    EXPECT_EQ(ring.at(0).pixel, 2u);
    EXPECT_TRUE(ring.fits(7));
    PixelJob c = ring.push({3, 0, 5, false});  // slots 9, 0, 1, 2, 3: wraps around
    EXPECT_EQ(c.first_slot, 9u);
    EXPECT_EQ(ring.nextSlot(), 4u);
    EXPECT_EQ(ring.nextJobPosition(), 3u);
    ring.popFront(5);  // more than in flight: all of them
    EXPECT_EQ(ring.inFlight(), 0u);
    EXPECT_EQ(ring.samplesInFlight(), 0u);
}

TEST(SampleRing, JobPositionsWrapAroundTheJobRing) {
    SampleRing ring(3);  // three slots, so three jobs at most
    for (int round = 0; round < 5; ++round) {
        size_t pos = ring.nextJobPosition();
        ring.push({uint32_t(round), 0, 1, false});
        EXPECT_EQ(pos, size_t(round) % 3);
        ring.popFront(1);
    }
}

// The refill prepares jobs before the round's wait (records written ahead of the pushes):
// what recordAhead and fitsAhead say must be what push and fits say once the jobs before
// are pushed.
TEST(SampleRing, RecordsAheadMatchThePushesThatFollow) {
    SampleRing ring(10);
    ring.push({0, 0, 4, false});  // slots 0-3
    ring.popFront(1);
    ring.push({1, 0, 3, false});  // slots 4-6; 3 in flight, next slot 7
    const PlannedJob a{2, 0, 4, false}, b{3, 0, 2, true}, c{4, 0, 2, false};
    EXPECT_TRUE(ring.fitsAhead(0, 0, a.count));
    const PixelJob ra = ring.recordAhead(0, a);
    EXPECT_TRUE(ring.fitsAhead(4, 1, b.count));
    const PixelJob rb = ring.recordAhead(4, b);
    EXPECT_FALSE(ring.fitsAhead(6, 2, c.count));  // 3 + 4 + 2 + 2 > 10 slots
    const PixelJob pa = ring.push(a), pb = ring.push(b);
    EXPECT_EQ(ra.first_slot, pa.first_slot);
    EXPECT_EQ(ra.first_slot, 7u);
    EXPECT_EQ(rb.first_slot, pb.first_slot);
    EXPECT_EQ(rb.first_slot, 1u);  // 7 + 4 wraps to 1
    EXPECT_EQ(rb.state, RT_JOB_LAST_TRY);
    EXPECT_EQ(ring.fits(c.count), ring.fitsAhead(0, 0, c.count));
    EXPECT_FALSE(ring.fits(c.count));
}

// The refill's host part (stageRefill), which the first pass makes on the planning
// thread: whole jobs from the queue's front up to the round cap (the first always), each
// job's record as the ring will book it, (pixel, sample) pairs, running sample ends; the
// ring's room cuts it too, and says so.
TEST(SampleRing, RefillStageTakesWholeJobsUpToTheCapOrTheRing) {
    SampleRing ring(8);
    const std::deque<PlannedJob> queue{{5, 0, 2, false}, {6, 3, 3, true}, {7, 0, 4, false}};
    RefillStage st;
    rd::stageRefill(ring, queue, 6, st);  // 2 + 3 fit the cap of 6; + 4 would not
    EXPECT_FALSE(st.ringBound);
    EXPECT_EQ(st.ends, (std::vector<uint32_t>{2, 5}));
    EXPECT_EQ(st.newSamples, (std::vector<uint32_t>{5, 0, 5, 1, 6, 3, 6, 4, 6, 5}));
    ASSERT_EQ(st.records.size(), 2u);
    EXPECT_EQ(st.records[1].first_slot, ring.recordAhead(2, queue[1]).first_slot);
    // (its first sample, 3, is odd: the Sobol sampler's second replicate, film.h)
    EXPECT_EQ(st.records[1].state, RT_JOB_LAST_TRY | RT_JOB_ODD_FIRST);
    EXPECT_EQ(st.records[0].state, RT_JOB_IN_FLIGHT);
    rd::stageRefill(ring, queue, 1, st);  // a job over the cap still goes first, alone
    EXPECT_EQ(st.ends, (std::vector<uint32_t>{2}));
    rd::stageRefill(ring, queue, 100, st);  // 2 + 3 + 4 > the ring's 8 slots
    EXPECT_TRUE(st.ringBound);
    EXPECT_EQ(st.ends, (std::vector<uint32_t>{2, 5}));
    const PixelJob p0 = ring.push(queue[0]), p1 = ring.push(queue[1]);  // as staged
    EXPECT_EQ(st.records[0].first_slot, p0.first_slot);
    EXPECT_EQ(st.records[1].first_slot, p1.first_slot);
    EXPECT_EQ(st.records[1].pixel, p1.pixel);
    EXPECT_EQ(st.records[1].count, 3u);
}

// A round retires thousands of one-sample jobs: the samples of the oldest n jobs and
// their release are O(1), and agree with the jobs' counts.
TEST(SampleRing, SamplesInFrontAddUpTheOldestJobs) {
    SampleRing ring(16);
    ring.push({0, 0, 3, false});
    ring.push({1, 0, 1, false});
    ring.push({2, 0, 5, false});
    EXPECT_EQ(ring.samplesInFront(0), 0u);
    EXPECT_EQ(ring.samplesInFront(2), 4u);
    EXPECT_EQ(ring.samplesInFront(9), 9u);  // clipped to the jobs in flight
    ring.popFront(2);
    EXPECT_EQ(ring.samplesInFlight(), 5u);
    EXPECT_EQ(ring.samplesInFront(1), 5u);
    ring.push({3, 0, 10, false});  // slots 9..18 wrap to 9..15, 0..2
    EXPECT_FALSE(ring.fits(2));    // 15 in flight of 16
    EXPECT_EQ(ring.samplesInFront(2), 15u);
    ring.popFront(1);
    EXPECT_TRUE(ring.fits(6));
    EXPECT_EQ(ring.at(0).pixel, 3u);
    EXPECT_EQ(ring.nextSlot(), 3u);
}

// Retire adds a job to the film without atomics only when it is its pixel's one job in
// the pass: a pixel with two requests (the first pass's block sample and its minimum) or
// a request cut into several jobs must keep the atomics.
TEST(SampleRing, OnlyAPixelsSoleJobIsExclusive) {
    std::vector<rd::PixelRequest> pass = {{1, 0, 1}, {2, 0, 1}, {2, 1, 1}, {3, 0, 9}, {4, 0, 4}};
    auto jobs = rd::planJobs(pass, 4, 8);
    ASSERT_EQ(jobs.size(), 7u);  // 1 | 1 | 1 | 4 + 4 + 1 | 4
    EXPECT_TRUE(jobs[0].exclusive);   // pixel 1: one job
    EXPECT_FALSE(jobs[1].exclusive);  // pixel 2: two requests
    EXPECT_FALSE(jobs[2].exclusive);
    EXPECT_FALSE(jobs[3].exclusive);  // pixel 3: cut into three jobs
    EXPECT_FALSE(jobs[5].exclusive);
    EXPECT_TRUE(jobs[6].exclusive);   // pixel 4: exactly maxJob samples, one job
    SampleRing ring(64);
    EXPECT_EQ(ring.push(jobs[0]).state, RT_JOB_IN_FLIGHT | RT_JOB_EXCLUSIVE);
    EXPECT_EQ(ring.push(jobs[1]).state, RT_JOB_IN_FLIGHT);
    PlannedJob again = jobs[6];
    again.lastTry = true;  // issued again after an abort: still the pixel's only job
    EXPECT_EQ(ring.push(again).state, RT_JOB_LAST_TRY | RT_JOB_EXCLUSIVE);
}

// An adaptive pass lists each pixel once: cut without the table of each pixel's jobs, its
// jobs are the same, exclusive marks included.
TEST(SampleRing, APassOfEachPixelOnceCutsTheSameWithoutTheTable) {
    std::vector<rd::PixelRequest> pass = {{1, 0, 1}, {3, 2, 9}, {4, 0, 4}, {9, 5, 5}, {7, 1, 2}};
    const auto a = rd::planJobs(pass, 4, 8), b = rd::planJobs(pass, 4, 8, true);
    ASSERT_EQ(a.size(), 8u);  // 1 | 4 + 4 + 1 | 4 | 4 + 1 | 2
    ASSERT_EQ(b.size(), a.size());
    for (size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(b[i].pixel, a[i].pixel);
        EXPECT_EQ(b[i].firstSample, a[i].firstSample);
        EXPECT_EQ(b[i].count, a[i].count);
        EXPECT_EQ(b[i].exclusive, a[i].exclusive) << i;  // (pixel 9 is past pixelCount)
    }
    EXPECT_TRUE(b[0].exclusive);
    EXPECT_FALSE(b[1].exclusive);
    EXPECT_TRUE(b[4].exclusive);
    EXPECT_FALSE(b[5].exclusive);
    EXPECT_TRUE(b[7].exclusive);
}

// A pipelined refill books every staged job before the device says how many fit, then
// takes the rest back (popBack): the ring is as if only those had been pushed, across the
// slot ring's wrap.
TEST(SampleRing, JobsTakenBackLeaveTheRingAsBefore) {
    SampleRing ring(10);
    ring.push({1, 0, 4, false});
    ring.push({2, 0, 3, false});
    ring.popFront(1);  // slots 4..6 in flight, the next is 7
    const size_t slot = ring.nextSlot(), pos = ring.nextJobPosition();
    const uint64_t inFlight = ring.samplesInFlight();
    ring.push({3, 0, 2, false});  // slots 7, 8
    ring.push({4, 0, 3, true});   // slots 9, 0, 1
    ring.popBack(1);
    EXPECT_EQ(ring.inFlight(), 2u);
    EXPECT_EQ(ring.samplesInFlight(), inFlight + 2);
    EXPECT_EQ(ring.nextSlot(), 9u);
    ring.popBack(1);
    EXPECT_EQ(ring.nextSlot(), slot);
    EXPECT_EQ(ring.nextJobPosition(), pos);
    EXPECT_EQ(ring.samplesInFlight(), inFlight);
    EXPECT_EQ(ring.at(0).pixel, 2u);
    PixelJob again = ring.push({4, 0, 3, true});  // pushed again: the same slots as before
    EXPECT_EQ(again.first_slot, 7u);
    ring.popBack(5);  // more than in flight: all of them, job 2 too
    EXPECT_EQ(ring.inFlight(), 0u);
    EXPECT_EQ(ring.samplesInFlight(), 0u);
    EXPECT_EQ(ring.nextSlot(), 4u);  // job 2's slots, after the retired job 1's
}
