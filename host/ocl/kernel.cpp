// kernel.cpp: kernel creation, launches and the profiling of their events.
#include "kernel.h"

#include <algorithm>

namespace rd {

Profiler::~Profiler() {
    for (Pending& p : m_pending) clReleaseEvent(p.event);
}

void Profiler::record(const std::string& kernel, cl_event ev, uint64_t launched) {
    KernelStats& s = m_stats[kernel];
    ++s.launches;
    s.launchedItems += launched;
    m_pending.push_back({kernel, ev, m_waitPending, launched});
    m_waitPending = false;
}

void Profiler::collect() {
    for (Pending& p : m_pending) {
        cl_ulong start = 0, end = 0;
        RD_CL_CHECK(clWaitForEvents(1, &p.event), m_ctx.name());
        if (clGetEventProfilingInfo(p.event, CL_PROFILING_COMMAND_START, sizeof start, &start,
                                    nullptr) == CL_SUCCESS &&
            clGetEventProfilingInfo(p.event, CL_PROFILING_COMMAND_END, sizeof end, &end,
                                    nullptr) == CL_SUCCESS &&
            end >= start) {
            m_stats[p.kernel].deviceMs += double(end - start) * 1e-6;
            // (an in-order queue: the events come in the order they ran)
            const double idleMs =
                m_lastEnd > 0 && start > m_lastEnd ? double(start - m_lastEnd) * 1e-6 : 0.0;
            (p.afterWait ? m_idleAfterWaitsMs : m_launchGapsMs) += idleMs;
            if (m_keepTimeline) {
                if (m_timeline.empty()) m_firstStart = start;
                m_timeline.push_back({p.kernel, double(start - std::min(start, m_firstStart)) * 1e-3,
                                      double(end - start) * 1e-3, idleMs * 1e3, p.launched,
                                      p.afterWait});
            }
            m_lastEnd = std::max(m_lastEnd, end);
        }
        clReleaseEvent(p.event);
    }
    m_pending.clear();
}

Kernel::Kernel(const ClContext& ctx, cl_program program, const std::string& name,
               Profiler& prof)
    : m_ctx(ctx), m_name(name), m_profiler(prof), m_active(ctx, 1) {
    cl_int err = CL_SUCCESS;
    m_kernel = clCreateKernel(program, name.c_str(), &err);
    RD_CL_CHECK(err, ctx.name());
    size_t maxWg = 0;
    clGetKernelWorkGroupInfo(m_kernel, ctx.device(), CL_KERNEL_WORK_GROUP_SIZE, sizeof maxWg,
                             &maxWg, nullptr);
    // 64 is a multiple of PoCL's vector width and of NVIDIA's warp; shrink only if the
    // kernel cannot run that wide on this device. A kernel that declares its size
    // (reqd_work_group_size: the compaction's RT_COMPACT_GROUP) runs at that size only,
    // whatever the device says of its kernels in general (rusticl: 32 for every kernel).
    while (maxWg && m_localSize > maxWg) m_localSize /= 2;
    size_t declared[3] = {0, 0, 0};
    if (clGetKernelWorkGroupInfo(m_kernel, ctx.device(), CL_KERNEL_COMPILE_WORK_GROUP_SIZE,
                                 sizeof declared, declared, nullptr) == CL_SUCCESS &&
        declared[0] > 0)
        m_localSize = declared[0];
    m_active.fillZero();
}

Kernel::~Kernel() {
    if (m_kernel) clReleaseKernel(m_kernel);
}

void Kernel::enqueue(size_t count) {
    if (count == 0) return;
    size_t global = (count + m_localSize - 1) / m_localSize * m_localSize;
    cl_event ev = nullptr;
    RD_CL_CHECK(clEnqueueNDRangeKernel(m_ctx.queue(), m_kernel, 1, nullptr, &global,
                                       &m_localSize, 0, nullptr, &ev),
                m_ctx.name() + "' running kernel '" + m_name);
    m_profiler.record(m_name, ev, global * m_lanes);
}

uint64_t Kernel::peekActive() const { return m_active.download()[0]; }

void Kernel::collectActive(const std::vector<Kernel*>& kernels) {
    if (kernels.empty()) return;
    for (Kernel* k : kernels) k->m_active.downloadRangeTo(0, 1, &k->m_activeRead, false);
    kernels.front()->m_ctx.finish();
    for (Kernel* k : kernels) {
        k->m_profiler.addActive(k->m_name, cl_uint(k->m_activeRead - k->m_activeCollected));
        k->m_activeCollected = k->m_activeRead;
    }
}

}  // namespace rd
