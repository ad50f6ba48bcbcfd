// device_film_sums.h: the film's error estimate and tally at the end of a frame, summed on
// the OpenCL device (cl/kernels/film_sums.cl) a batch of pixels at a time and added up
// here in batch order: the same values as estimateFilmErrors and Film::tally on the host,
// without the host reading every pixel while the device waits. Needs double precision
// on the device (DeviceInfo::fp64).
#pragma once
#include "film/film.h"
#include "film/film_error.h"
#include "ocl/buffer.h"
#include "ocl/host_memory.h"
#include "ocl/kernel.h"

namespace rd {

struct FilmSummary {
    FilmError error;
    Film::Tally tally;
};

class DeviceFilmSums {
public:
    // `program` holds film_sums.cl's kernel; `film` (its size and crop window) is the film
    // `filmBuf` holds.
    DeviceFilmSums(const ClContext& ctx, cl_program program, Profiler& prof,
                   const DeviceBuffer<PixelAccum>& filmBuf, const Film& film);
    // Queues the sums and their reads; summary() once the queue has finished.
    void launch();
    FilmSummary summary() const;
    Kernel& kernel() { return m_sums; }

private:
    const DeviceBuffer<PixelAccum>& m_filmBuf;
    cl_uint m_count, m_width;
    cl_uint4 m_crop;
    Kernel m_sums;
    HostVector<double> m_sumsHost;
    HostVector<uint32_t> m_countsHost;
    HostVector<uint64_t> m_tallyHost;
    DeviceBuffer<double> m_sumsBuf;
    DeviceBuffer<uint32_t> m_countsBuf;
    DeviceBuffer<uint64_t> m_tallyBuf;
};

}  // namespace rd
