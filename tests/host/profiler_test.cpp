// profiler_test.cpp: the profiler's split of the device's idle time between kernels
// (host/ocl/kernel.h): idle after the host said it waits (a round's end, planning) is
// the host's; idle between kernels queued back to back is the runtime's launch gap.
// --stats reports the two apart (host_sync_overhead, launch_gaps_ms).
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
