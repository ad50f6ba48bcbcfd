// kernel.h: named kernel launches with event profiling. Every launch records its event;
// Profiler::collect() turns events into per-kernel device time and reads each kernel's
// active-work-item counter, giving the occupancy figure of --stats (active / launched).
#pragma once
#include <map>
#include <string>
#include <type_traits>
#include <vector>

#include "buffer.h"

namespace rd {

struct KernelStats {
    uint64_t launches = 0;
    uint64_t launchedItems = 0; // global work size, rounded up to the local size
    uint64_t activeItems = 0;   // work-items that had real work (counted on the device)
    double deviceMs = 0;
    double occupancy() const {
        return launchedItems ? double(activeItems) / double(launchedItems) : 0.0;
    }
};

// One kernel run as the device ran it (Profiler::keepTimeline, raydrive --timeline):
// microseconds on the device clock from the profiler's first kernel, and the device's idle
// time just before it, the host's (after a host wait) or the runtime's (a launch gap).
struct TimelineEvent {
    std::string kernel;
    double startUs = 0, durationUs = 0, idleBeforeUs = 0;
    uint64_t launchedItems = 0;
    bool afterWait = false;
};

class Profiler {
public:
    explicit Profiler(const ClContext& ctx) : m_ctx(ctx) {}
    ~Profiler();
    void record(const std::string& kernel, cl_event ev, uint64_t launched);
    void addActive(const std::string& kernel, uint64_t active) {
        m_stats[kernel].activeItems += active;
    }
    // Waits for the recorded events and adds their device time; cheap to call often.
    void collect();
    const std::map<std::string, KernelStats>& stats() const { return m_stats; }
    // The host is about to wait for the device (or has just waited): the idle time
    // before the next kernel is the host's, not the runtime's.
    void markHostWait() { m_waitPending = true; }
    // Device idle time between consecutive kernels, in ms (event start after the end of
    // the kernel before): after a host wait, and between kernels the host had already
    // queued (the runtime's own cost of a launch).
    double idleAfterWaitsMs() const { return m_idleAfterWaitsMs; }
    double launchGapsMs() const { return m_launchGapsMs; }
    // Keep every kernel run from now on, in the order they ran (collect() adds them).
    void keepTimeline() { m_keepTimeline = true; }
    const std::vector<TimelineEvent>& timeline() const { return m_timeline; }

private:
    struct Pending {
        std::string kernel;
        cl_event event;
        bool afterWait;
        uint64_t launched;
    };
    const ClContext& m_ctx;
    std::vector<Pending> m_pending;
    std::map<std::string, KernelStats> m_stats;
    bool m_waitPending = false;
    cl_ulong m_lastEnd = 0;  // device clock, ns; 0 before the first kernel
    double m_idleAfterWaitsMs = 0, m_launchGapsMs = 0;
    bool m_keepTimeline = false;
    cl_ulong m_firstStart = 0;  // the timeline's zero, device clock, ns
    std::vector<TimelineEvent> m_timeline;
};

class Kernel {
public:
    Kernel(const ClContext& ctx, cl_program program, const std::string& name, Profiler& prof);
    ~Kernel();
    Kernel(const Kernel&) = delete;
    Kernel& operator=(const Kernel&) = delete;

    // Sets the arguments in order, appends the kernel's active counter as the last one,
    // and enqueues `count` work-items rounded up to a multiple of `localSize`.
    template <typename... Args>
    void launch(size_t count, const Args&... args) {
        cl_uint index = 0;
        (setArg(index++, args), ...);
        setArg(index, m_active);
        enqueue(count);
    }
    // Adds what the device counter gained since the last collection to the profiler.
    void collectActive() { collectActive({this}); }
    // The same for several kernels (of one context) at one wait: a blocking read each
    // costs a round trip.
    static void collectActive(const std::vector<Kernel*>& kernels);
    // The device counter as it stands (a blocking read): work-items since the start.
    uint64_t peekActive() const;
    const std::string& name() const { return m_name; }
    size_t localSize() const { return m_localSize; }
    // A work-item of this kernel takes `lanes` rays (a packet kernel): its occupancy
    // counts rays against lanes launched.
    void setLanesPerItem(size_t lanes) { m_lanes = lanes; }

private:
    template <typename T>
    void setArg(cl_uint i, const DeviceBuffer<T>& b) {
        cl_mem m = b.mem();
        RD_CL_CHECK(clSetKernelArg(m_kernel, i, sizeof(cl_mem), &m), m_ctx.name());
    }
    template <typename T, typename = std::enable_if_t<std::is_trivially_copyable_v<T>>>
    void setArg(cl_uint i, const T& v) {
        RD_CL_CHECK(clSetKernelArg(m_kernel, i, sizeof(T), &v), m_ctx.name());
    }
    void enqueue(size_t count);
    cl_uint m_activeRead = 0;       // the counter, read without blocking
    cl_uint m_activeCollected = 0;  // its value at the last collection (it wraps)

    const ClContext& m_ctx;
    std::string m_name;
    Profiler& m_profiler;
    cl_kernel m_kernel = nullptr;
    size_t m_localSize = 64;
    size_t m_lanes = 1;
    DeviceBuffer<cl_uint> m_active;
};

}  // namespace rd
