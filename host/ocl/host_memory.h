// host_memory.h: host arrays an OpenCL device may use in place (CL_MEM_USE_HOST_PTR).
// A CPU runtime (PoCL) takes page-aligned host memory as the buffer itself, so mapping
// it for reading copies nothing (12 MB film: 0.04 ms against 0.4-0.6 ms for a read);
// a discrete GPU copies at the map as a read would.
#pragma once
#include <cstdlib>
#include <new>
#include <vector>

namespace rd {

template <typename T>
struct PageAlignedAllocator {
    using value_type = T;
    static constexpr size_t kAlign = 4096;
    PageAlignedAllocator() = default;
    template <typename U>
    PageAlignedAllocator(const PageAlignedAllocator<U>&) {}
    T* allocate(size_t n) {
        void* p = nullptr;
        if (posix_memalign(&p, kAlign, (n ? n : 1) * sizeof(T)) != 0) throw std::bad_alloc();
        return static_cast<T*>(p);
    }
    void deallocate(T* p, size_t) { std::free(p); }
    template <typename U>
    bool operator==(const PageAlignedAllocator<U>&) const { return true; }
    template <typename U>
    bool operator!=(const PageAlignedAllocator<U>&) const { return false; }
};

template <typename T>
using HostVector = std::vector<T, PageAlignedAllocator<T>>;

}  // namespace rd
