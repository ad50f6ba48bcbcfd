// buffer.h: a typed device buffer with RAII release, sized in elements. Transfers are
// blocking by default: the host needs their data at once, and the in-order queue keeps
// kernel order anyway.
#pragma once
#include <algorithm>
#include <utility>
#include <vector>

#include "check.h"
#include "context.h"
#include "host_memory.h"

namespace rd {

template <typename T>
class DeviceBuffer {
public:
    DeviceBuffer() = default;
    DeviceBuffer(const ClContext& ctx, size_t count, cl_mem_flags flags = CL_MEM_READ_WRITE)
        : m_ctx(&ctx), m_count(count) {
        cl_int err = CL_SUCCESS;
        // A zero-sized buffer is invalid in OpenCL; keep one element so kernels always
        // get a valid argument for a feature the scene does not use.
        m_mem = clCreateBuffer(ctx.context(), flags, sizeof(T) * (count ? count : 1), nullptr,
                               &err);
        RD_CL_CHECK(err, ctx.name());
    }
    // A buffer over host memory the host keeps (CL_MEM_USE_HOST_PTR), its first contents
    // taken from there: `host` must outlive the buffer and stay where it is. The host
    // sees the device's writes after syncToHost().
    // (Only a HostVector: any other vector is copied, by the constructor below.)
    DeviceBuffer(const ClContext& ctx, HostVector<T>& host)
        : m_ctx(&ctx), m_count(host.size()), m_host(host.empty() ? nullptr : host.data()) {
        cl_int err = CL_SUCCESS;
        m_mem = m_host ? clCreateBuffer(ctx.context(), CL_MEM_READ_WRITE | CL_MEM_USE_HOST_PTR,
                                        bytes(), m_host, &err)
                       : clCreateBuffer(ctx.context(), CL_MEM_READ_WRITE, sizeof(T), nullptr,
                                        &err);
        RD_CL_CHECK(err, ctx.name());
    }
    DeviceBuffer(const ClContext& ctx, const std::vector<T>& data,
                 cl_mem_flags flags = CL_MEM_READ_ONLY)
        : DeviceBuffer(ctx, data.size(), flags) {
        if (!data.empty()) upload(data);
    }
    ~DeviceBuffer() { release(); }
    DeviceBuffer(DeviceBuffer&& o) noexcept { *this = std::move(o); }
    DeviceBuffer& operator=(DeviceBuffer&& o) noexcept {
        if (this != &o) {
            release();
            m_ctx = o.m_ctx;
            m_mem = std::exchange(o.m_mem, nullptr);
            m_count = std::exchange(o.m_count, 0);
            m_host = std::exchange(o.m_host, nullptr);
        }
        return *this;
    }
    DeviceBuffer(const DeviceBuffer&) = delete;
    DeviceBuffer& operator=(const DeviceBuffer&) = delete;

    cl_mem mem() const { return m_mem; }
    size_t size() const { return m_count; }
    size_t bytes() const { return m_count * sizeof(T); }

    void upload(const std::vector<T>& data) { write(0, data.data(), data.size(), true); }
    // Writes count elements from data at element offset first (texture tiles).
    void uploadRange(size_t first, const T* data, size_t count) {
        write(first, data, count, true);
    }
    // The same without waiting: `data` must stay unchanged until the queue has run the
    // write (the next blocking read or finish on this in-order queue), which spares the
    // render loop a round trip per small upload.
    void uploadAsync(size_t first, const T* data, size_t count) {
        write(first, data, count, false);
    }
    // Copies count elements from this buffer at srcFirst into dst at dstFirst, on the device.
    void copyTo(DeviceBuffer& dst, size_t srcFirst, size_t dstFirst, size_t count) const {
        if (count)
            RD_CL_CHECK(clEnqueueCopyBuffer(m_ctx->queue(), m_mem, dst.m_mem, sizeof(T) * srcFirst,
                                            sizeof(T) * dstFirst, sizeof(T) * count, 0, nullptr,
                                            nullptr),
                        m_ctx->name());
    }
    // count elements from first on into out; without blocking, out must live until a
    // later blocking command on the queue has returned, or `done` (when given: the read's
    // event, for ClContext::wait; none when count is 0) has completed.
    void downloadRangeTo(size_t first, size_t count, T* out, bool blocking,
                         cl_event* done = nullptr) const {
        if (count)
            RD_CL_CHECK(
                clEnqueueReadBuffer(m_ctx->queue(), m_mem, blocking ? CL_TRUE : CL_FALSE,
                                    sizeof(T) * first, sizeof(T) * count, out, 0, nullptr,
                                    done),
                m_ctx->name());
    }
    // count elements from first on (clipped to the buffer).
    std::vector<T> downloadRange(size_t first, size_t count) const {
        std::vector<T> out(first < m_count ? std::min(count, m_count - first) : 0);
        downloadRangeTo(first, out.size(), out.data(), true);
        return out;
    }
    // The first count elements (the rest need not be read).
    std::vector<T> downloadFirst(size_t count) const { return downloadRange(0, count); }
    std::vector<T> download() const { return downloadRange(0, m_count); }
    // The whole buffer into `out`, resized to fit: a vector kept from read to read is not
    // allocated, cleared and faulted in again. Not blocking: `out` holds the data after
    // the queue's next finish, and must not be touched before (it overlaps the copy with
    // the host's work).
    void downloadInto(std::vector<T>& out, bool blocking = true) const {
        out.resize(m_count);
        downloadRangeTo(0, m_count, out.data(), blocking);
    }
    // A buffer over host memory: brings the device's writes into it (a map for reading and
    // its unmap; on a CPU device nothing is copied). Without blocking, the memory holds
    // them after the queue's next finish and must not be read before.
    void syncToHost(bool blocking = true) {
        if (!m_host) return;
        cl_int err = CL_SUCCESS;
        const bool block = blocking || m_ctx->info().mapMustBlock();
        void* p = clEnqueueMapBuffer(m_ctx->queue(), m_mem, block ? CL_TRUE : CL_FALSE,
                                     CL_MAP_READ, 0, bytes(), 0, nullptr, nullptr, &err);
        RD_CL_CHECK(err, m_ctx->name());
        RD_CL_CHECK(clEnqueueUnmapMemObject(m_ctx->queue(), m_mem, p, 0, nullptr, nullptr),
                    m_ctx->name());
    }
    void fillZero() {
        const unsigned char zero = 0;
        RD_CL_CHECK(clEnqueueFillBuffer(m_ctx->queue(), m_mem, &zero, 1, 0,
                                        sizeof(T) * (m_count ? m_count : 1), 0, nullptr,
                                        nullptr),
                    m_ctx->name());
    }

private:
    void write(size_t first, const T* data, size_t count, bool blocking) {
        if (count)
            RD_CL_CHECK(clEnqueueWriteBuffer(m_ctx->queue(), m_mem, blocking ? CL_TRUE : CL_FALSE,
                                             sizeof(T) * first, sizeof(T) * count, data, 0,
                                             nullptr, nullptr),
                        m_ctx->name());
    }
    void release() {
        if (m_mem) clReleaseMemObject(m_mem);
        m_mem = nullptr;
    }
    const ClContext* m_ctx = nullptr;
    cl_mem m_mem = nullptr;
    size_t m_count = 0;
    T* m_host = nullptr;  // the host memory a buffer over it uses
};

}  // namespace rd
