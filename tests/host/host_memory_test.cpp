// host_memory_test.cpp: device buffers over host memory (host/ocl/host_memory.h,
// DeviceBuffer's host-memory constructor and syncToHost), as the film uses them: the
// buffer starts with the host's contents, and the host sees the device's writes after a
// sync, blocking or not, round after round.
#include <gtest/gtest.h>

#include <cstdint>

#include "ocl/buffer.h"
#include "ocl/host_memory.h"
#include "ocl/kernel.h"
#include "ocl/program.h"
#include "render_harness.h"

using namespace rd;

TEST(HostMemory, PageAligned) {
    HostVector<float> v(1000, 1.0f);
    EXPECT_EQ(reinterpret_cast<uintptr_t>(v.data()) % 4096, 0u);
    v.resize(100000);
    EXPECT_EQ(reinterpret_cast<uintptr_t>(v.data()) % 4096, 0u);
    EXPECT_EQ(v[999], 1.0f);
}

TEST(HostMemory, BufferOverHostMemorySyncsEachRound) {
    const ClContext& ctx = test::testContext();
    Program program(ctx,
                    "__kernel void add(uint n, float k, __global float* v, __global uint* active) {\n"
                    "    size_t i = get_global_id(0);\n"
                    "    if (i < n) v[i] += k * (float)i;\n}\n",
                    "-cl-std=CL1.2");
    Profiler prof(ctx);
    Kernel add(ctx, program.get(), "add", prof);
    const size_t n = 3000;  // not a whole page
    HostVector<float> host(n, 2.0f);
    const float* where = host.data();
    DeviceBuffer<float> buf(ctx, host);
    add.launch(n, cl_uint(n), 1.0f, buf);
    buf.syncToHost();
    EXPECT_EQ(host.data(), where);
    for (size_t i = 0; i < n; ++i) ASSERT_EQ(host[i], 2.0f + float(i)) << i;
    add.launch(n, cl_uint(n), 0.5f, buf);  // the next round starts from what the device had
    buf.syncToHost(/*blocking=*/false);
    ctx.finish();
    for (size_t i = 0; i < n; ++i) ASSERT_EQ(host[i], 2.0f + 1.5f * float(i)) << i;
    HostVector<float> none;
    DeviceBuffer<float> empty(ctx, none);  // a valid argument, nothing to sync
    empty.syncToHost();
    EXPECT_EQ(empty.size(), 0u);
}
