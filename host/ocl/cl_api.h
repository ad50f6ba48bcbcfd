// cl_api.h: the one place the OpenCL C API is included, pinned to OpenCL 1.2 so the host
// runs on every device that RayDrive targets (PoCL, NVIDIA, AMD, Intel).
#pragma once
#ifndef CL_TARGET_OPENCL_VERSION
#define CL_TARGET_OPENCL_VERSION 120
#endif
#include <CL/cl.h>
