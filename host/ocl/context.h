// context.h: one OpenCL context and in-order profiling queue on the chosen device, with
// RAII ownership. Everything that talks to the device goes through a ClContext.
#pragma once
#include <string>

#include "device.h"

namespace rd {

class ClContext {
public:
    explicit ClContext(const DeviceInfo& device);
    ~ClContext();
    ClContext(const ClContext&) = delete;
    ClContext& operator=(const ClContext&) = delete;

    cl_context context() const { return m_context; }
    cl_command_queue queue() const { return m_queue; }
    cl_device_id device() const { return m_info.device; }
    const DeviceInfo& info() const { return m_info; }
    const std::string& name() const { return m_info.name; }
    void finish() const;
    // Waits for one command (and, the queue being in order, all before it) and releases
    // its event; the commands queued after it go on running.
    void wait(cl_event done) const;

private:
    DeviceInfo m_info;
    cl_context m_context = nullptr;
    cl_command_queue m_queue = nullptr;
};

}  // namespace rd
