// layout_test.cpp: every struct in cl/include/ has the same size and field offsets on the
// device as on the host. The list of fields is cl/include/layout_fields.h, expanded here
// with the host's offsetof and on the device by layout_probe.cl, on every device present.
#include <gtest/gtest.h>

#include <cstddef>
#include <filesystem>

#include "cl/include/all_types.h"
#include "ocl/buffer.h"
#include "ocl/device.h"
#include "ocl/kernel.h"
#include "ocl/program.h"

using namespace rd;

namespace {

struct Entry {
    std::string what;
    uint32_t value;
};

std::vector<Entry> hostLayout() {
    std::vector<Entry> v;
#define RT_STRUCT(T) v.push_back({"sizeof(" #T ")", uint32_t(sizeof(T))});
#define RT_FIELD(T, f) v.push_back({"offsetof(" #T ", " #f ")", uint32_t(offsetof(T, f))});
#include "cl/include/layout_fields.h"
#undef RT_STRUCT
#undef RT_FIELD
    return v;
}

}  // namespace

TEST(Layout, DeviceMatchesHostOnEveryDevice) {
    std::vector<Entry> host = hostLayout();
    ASSERT_GT(host.size(), 20u);
    for (const DeviceInfo& d : listDevices()) {
        SCOPED_TRACE(d.name);
        ClContext ctx(d);
        Program program(ctx, assembleClSource({"layout_probe.cl"}), "-cl-std=CL1.2", "");
        Profiler prof(ctx);
        cl_int err = CL_SUCCESS;
        cl_kernel k = clCreateKernel(program.get(), "layout_probe", &err);
        ASSERT_EQ(err, CL_SUCCESS);
        DeviceBuffer<cl_uint> out(ctx, host.size());
        cl_mem m = out.mem();
        clSetKernelArg(k, 0, sizeof m, &m);
        size_t one = 1;
        ASSERT_EQ(clEnqueueNDRangeKernel(ctx.queue(), k, 1, nullptr, &one, &one, 0, nullptr,
                                         nullptr),
                  CL_SUCCESS);
        std::vector<cl_uint> dev = out.download();
        clReleaseKernel(k);
        for (size_t i = 0; i < host.size(); ++i)
            EXPECT_EQ(dev[i], host[i].value) << host[i].what << " differs on the device";
    }
}
