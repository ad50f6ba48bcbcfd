/* compat.h: lets every header under cl/include/ compile both as OpenCL C 1.2 and as C++17.
 * Shared structs use only 32-bit scalars, rt_float4 and fixed arrays; never float3, bool,
 * size_t or pointers, so that host and device agree on every offset (checked by
 * tests/layout_test.cpp against cl/kernels/layout_probe.cl on the device). */
#ifndef RT_COMPAT_H
#define RT_COMPAT_H

#ifdef __OPENCL_C_VERSION__
typedef uint uint32_t;
typedef int int32_t;
typedef float4 rt_float4;
#define RT_ALIGN16 __attribute__((aligned(16)))
#else
#include <cstddef>
#include <cstdint>
namespace rt_detail {}
struct alignas(16) rt_float4 {
    float x, y, z, w;
};
#define RT_ALIGN16 alignas(16)
#define RT_ASSERT_SIZE(T, n) static_assert(sizeof(T) == (n), "size of " #T " changed")
#endif

#endif
