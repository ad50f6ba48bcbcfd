// profiler_test.cpp: the profiler's split of the device's idle time between kernels
// (host/ocl/kernel.h): idle after the host said it waits (a round's end, planning) is
// the host's; idle between kernels queued back to back is the runtime's launch gap.
// --stats reports the two apart (host_sync_overhead, launch_gaps_ms); --timeline keeps each
// run with the idle time before it.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "ocl/buffer.h"
#include "ocl/kernel.h"
#include "ocl/program.h"
#include "render_harness.h"

using namespace rd;

TEST(Profiler, IdleAfterAHostWaitIsNotALaunchGap) {
    const ClContext& ctx = test::testContext();
    Program program(ctx,
                    "__kernel void busy(uint n, __global float* out, __global uint* active) {\n"
                    "    float x = (float)get_global_id(0);\n"
                    "    for (uint i = 0; i < n; ++i) x = x * 0.999f + 1.0f;\n"
                    "    out[get_global_id(0)] = x;\n}\n",
                    "-cl-std=CL1.2");
    Profiler prof(ctx);
    Kernel k(ctx, program.get(), "busy", prof);
    DeviceBuffer<float> out(ctx, 64);
    k.launch(64, cl_uint(1000), out);  // first launch: the runtime's one-off set-up
    ctx.finish();
    prof.collect();
    const double gapsBefore = prof.launchGapsMs();
    k.launch(64, cl_uint(1000), out);  // after a finish nobody marked: a launch gap
    k.launch(64, cl_uint(1000), out);
    ctx.finish();
    prof.markHostWait();
    std::this_thread::sleep_for(std::chrono::milliseconds(40));  // the host's work
    k.launch(64, cl_uint(1000), out);
    ctx.finish();
    prof.collect();
    EXPECT_EQ(prof.stats().at("busy").launches, 4u);
    EXPECT_GE(prof.idleAfterWaitsMs(), 35.0) << "the 40 ms the host slept, device clock";
    EXPECT_LT(prof.idleAfterWaitsMs(), 1000.0);
    EXPECT_GE(prof.launchGapsMs(), gapsBefore);
    EXPECT_LT(prof.launchGapsMs() - gapsBefore, 35.0) << "no host sleep between these";
}

// The timeline (--timeline) keeps every run in the order the device ran them: their
// device times add up to the per-kernel totals, none overlaps the one before, and the
// idle time before each is the host's after a marked wait (the 40 ms the host slept),
// otherwise the runtime's.
TEST(Profiler, TimelineKeepsEveryRunInOrder) {
    const ClContext& ctx = test::testContext();
    Program program(ctx,
                    "__kernel void spin(uint n, __global float* out, __global uint* active) {\n"
                    "    float x = (float)get_global_id(0);\n"
                    "    for (uint i = 0; i < n; ++i) x = x * 0.999f + 1.0f;\n"
                    "    out[get_global_id(0)] = x;\n}\n"
                    "__kernel void spin2(uint n, __global float* out, __global uint* active) {\n"
                    "    out[get_global_id(0)] = (float)n;\n}\n",
                    "-cl-std=CL1.2");
    Profiler prof(ctx);
    prof.keepTimeline();
    Kernel a(ctx, program.get(), "spin", prof), b(ctx, program.get(), "spin2", prof);
    DeviceBuffer<float> out(ctx, 128);
    a.launch(64, cl_uint(1000), out);
    b.launch(128, cl_uint(1), out);
    ctx.finish();
    prof.markHostWait();
    std::this_thread::sleep_for(std::chrono::milliseconds(40));
    a.launch(64, cl_uint(1000), out);
    b.launch(128, cl_uint(1), out);
    ctx.finish();
    prof.collect();
    const std::vector<TimelineEvent>& tl = prof.timeline();
    ASSERT_EQ(tl.size(), 4u);
    const char* names[] = {"spin", "spin2", "spin", "spin2"};
    double sumSpin = 0;
    for (size_t i = 0; i < tl.size(); ++i) {
        EXPECT_EQ(tl[i].kernel, names[i]) << i;
        EXPECT_GE(tl[i].durationUs, 0.0);
        if (i > 0) {  // an in-order queue: each starts after the one before ended
            EXPECT_GE(tl[i].startUs, tl[i - 1].startUs + tl[i - 1].durationUs - 1e-3) << i;
            EXPECT_NEAR(tl[i].startUs - tl[i - 1].startUs - tl[i - 1].durationUs,
                        tl[i].idleBeforeUs, 1e-3) << i;
        }
        if (tl[i].kernel == "spin") sumSpin += tl[i].durationUs;
    }
    EXPECT_EQ(tl[0].startUs, 0.0);
    EXPECT_EQ(tl[0].launchedItems, 64u);
    EXPECT_EQ(tl[1].launchedItems, 128u);
    EXPECT_NEAR(sumSpin * 1e-3, prof.stats().at("spin").deviceMs, 1e-6);
    EXPECT_TRUE(tl[2].afterWait);
    EXPECT_FALSE(tl[1].afterWait || tl[3].afterWait);
    EXPECT_GE(tl[2].idleBeforeUs, 35e3) << "the host's 40 ms";
    EXPECT_NEAR(tl[2].idleBeforeUs * 1e-3, prof.idleAfterWaitsMs(), 1e-6);
}
