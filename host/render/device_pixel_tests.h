// device_pixel_tests.h: the planner's test of every pixel on the OpenCL device
// (cl/kernels/pixel_tests.cl): the first adaptive pass's means, brightness floor sums and
// per-pixel requests from the film where retire_samples left it, so that the host only
// gathers the requests (benchmarks/README "The planner's test on the device"). Needs
// double precision on the device (DeviceInfo::fp64).
#pragma once
#include <vector>

#include "cl/include/film.h"
#include "ocl/buffer.h"
#include "ocl/host_memory.h"
#include "ocl/kernel.h"
#include "sampling.h"

namespace rd {

// The host memory the device's answers land in (a CPU device writes it in place),
// allocated and touched ahead, off the render loop (the thread that plans the first
// pass): its first touch by the kernels cost 1.2 ms of page faults on a 512x512 frame.
struct PixelTestMemory {
    PixelTestMemory(const SamplePlanner& planner, int width, int height);
    HostVector<float> meanOf, errorOf, relErr;
    HostVector<uint8_t> edge;
    HostVector<uint32_t> more, request;  // two words a pixel
};

class DevicePixelTests final : public PixelTester {
public:
    // `program` holds pixel_tests.cl's kernels; `film` is the film of width x height
    // pixels `planner` reads (its settings and pixel order are taken here).
    DevicePixelTests(const ClContext& ctx, cl_program program, Profiler& prof,
                     const DeviceBuffer<PixelAccum>& film, int width, int height,
                     const SamplePlanner& planner, PixelTestMemory&& memory);
    void means(float* meanOf, double* groupSums, double* groupCounts) override;
    Answers test(bool meansTaken, float floor, float pixelError,
                 const std::vector<uint8_t>& busy) override;
    std::vector<Kernel*> kernels() { return {&m_means, &m_meanSums, &m_tests}; }

private:
    // film_means and film_mean_sums: the means, errors, requests, sums and edges.
    void launchMeans();
    Profiler& m_prof;
    const DeviceBuffer<PixelAccum>& m_film;
    cl_uint m_width, m_height;
    SamplingSettings m_settings;
    PixelTestMemory m_mem;
    Kernel m_means, m_meanSums, m_tests;
    DeviceBuffer<uint32_t> m_rank;
    DeviceBuffer<float> m_meanOf, m_errorOf, m_relErr;
    DeviceBuffer<uint8_t> m_edge;
    DeviceBuffer<uint32_t> m_more, m_request;
    DeviceBuffer<double> m_groupSums, m_groupCounts;
    DeviceBuffer<uint8_t> m_busy;
};

}  // namespace rd
