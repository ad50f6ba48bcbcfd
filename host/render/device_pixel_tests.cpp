// device_pixel_tests.cpp: the planner's test of every pixel on the device
// (device_pixel_tests.h).
#include "device_pixel_tests.h"

#include <cmath>

#include "film/film_error_batch.h"

namespace rd {

PixelTestMemory::PixelTestMemory(const SamplePlanner& planner, int width, int height)
    : meanOf(size_t(width) * size_t(height)),
      errorOf(size_t(width) * size_t(height)),
      // (pixels off the crop window are never written: their own)
      relErr(size_t(width) * size_t(height), NAN),
      edge(size_t(width) * size_t(height)),
      more(2 * size_t(width) * size_t(height)),
      request(2 * planner.pixelOrder().size()) {}

DevicePixelTests::DevicePixelTests(const ClContext& ctx, cl_program program, Profiler& prof,
                                   const DeviceBuffer<PixelAccum>& film, int width,
                                   int height, const SamplePlanner& planner,
                                   PixelTestMemory&& memory)
    : m_prof(prof),
      m_film(film),
      m_width(cl_uint(width)),
      m_height(cl_uint(height)),
      m_settings(planner.settings()),
      m_mem(std::move(memory)),
      m_means(ctx, program, "film_means", prof),
      m_meanSums(ctx, program, "film_mean_sums", prof),
      m_tests(ctx, program, "film_tests", prof),
      m_rank(ctx, planner.pixelRank()),
      m_meanOf(ctx, m_mem.meanOf),
      m_errorOf(ctx, m_mem.errorOf),
      m_relErr(ctx, m_mem.relErr),
      m_edge(ctx, m_mem.edge),
      m_more(ctx, m_mem.more),
      m_request(ctx, m_mem.request),
      m_groupSums(ctx, (size_t(width) * size_t(height) + kPixelBatch - 1) / kPixelBatch),
      m_groupCounts(ctx, m_groupSums.size()),
      m_busy(ctx, size_t(width) * size_t(height), CL_MEM_READ_ONLY) {
    m_busy.fillZero();  // (read whether or not a test has busy pixels)
}

void DevicePixelTests::launchMeans() {
    const cl_uint pixels = m_width * m_height;
    m_means.launch((pixels + 3) / 4, pixels, cl_uint(m_settings.minSamples),
                   cl_uint(m_settings.maxSamples), m_film, m_meanOf, m_errorOf, m_more);
    m_meanSums.launch(m_groupSums.size(), m_width, m_height, m_meanOf, m_groupSums,
                      m_groupCounts, m_edge, m_settings.contrast);
}

void DevicePixelTests::means(float* meanOf, double* groupSums, double* groupCounts) {
    launchMeans();
    m_prof.markHostWait();  // (the floor needs the sums before the test can run)
    m_meanOf.downloadRangeTo(0, m_width * m_height, meanOf, /*blocking=*/false);
    m_groupSums.downloadRangeTo(0, m_groupSums.size(), groupSums, /*blocking=*/false);
    m_groupCounts.downloadRangeTo(0, m_groupCounts.size(), groupCounts, /*blocking=*/true);
}

PixelTester::Answers DevicePixelTests::test(bool meansTaken, float floor, float pixelError,
                                            const std::vector<uint8_t>& busy) {
    if (!meansTaken) launchMeans();
    if (!busy.empty()) m_busy.uploadAsync(0, busy.data(), busy.size());
    const cl_uint pixels = m_width * m_height;
    m_tests.launch(pixels, pixels, m_rank, m_meanOf, m_errorOf, m_edge, m_more, m_busy,
                   cl_uint(!busy.empty()), floor, pixelError, m_relErr, m_request);
    m_prof.markHostWait();
    m_request.syncToHost(/*blocking=*/false);
    m_relErr.syncToHost(/*blocking=*/true);
    return {m_mem.request.data(), m_mem.relErr.data()};
}

}  // namespace rd
