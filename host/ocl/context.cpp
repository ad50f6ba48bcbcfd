// context.cpp: creating and releasing the context and its profiling queue.
#include "context.h"

#include "check.h"

namespace rd {

ClContext::ClContext(const DeviceInfo& device) : m_info(device) {
    cl_int err = CL_SUCCESS;
    cl_context_properties props[] = {CL_CONTEXT_PLATFORM,
                                     reinterpret_cast<cl_context_properties>(device.platform),
                                     0};
    m_context = clCreateContext(props, 1, &m_info.device, nullptr, nullptr, &err);
    RD_CL_CHECK(err, m_info.name);
    m_queue = clCreateCommandQueue(m_context, m_info.device, CL_QUEUE_PROFILING_ENABLE, &err);
    if (err != CL_SUCCESS) {
        clReleaseContext(m_context);
        RD_CL_CHECK(err, m_info.name);
    }
}

ClContext::~ClContext() {
    if (m_queue) clReleaseCommandQueue(m_queue);
    if (m_context) clReleaseContext(m_context);
}

void ClContext::finish() const { RD_CL_CHECK(clFinish(m_queue), m_info.name); }

void ClContext::wait(cl_event done) const {
    struct Release {
        cl_event ev;
        ~Release() { clReleaseEvent(ev); }
    } release{done};
    RD_CL_CHECK(clWaitForEvents(1, &done), m_info.name);
}

}  // namespace rd
