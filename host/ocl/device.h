// device.h: OpenCL device discovery and selection. `raydrive devices` lists what is here;
// `--device N|name-substring` or RAYDRIVE_DEVICE picks one; the default is the PoCL CPU
// device when present (the device every test runs on), else the first GPU, else device 0.
#pragma once
#include <string>
#include <vector>

#include "cl_api.h"

namespace rd {

struct DeviceInfo {
    int index = 0; // position in the flattened list across platforms
    cl_platform_id platform = nullptr;
    cl_device_id device = nullptr;
    std::string platformName, name, vendor, version, driverVersion;
    cl_device_type type = 0;
    cl_uint computeUnits = 0;
    cl_ulong globalMemBytes = 0, maxAllocBytes = 0;
    size_t maxWorkGroupSize = 0;
    bool fp64 = false;  // double precision (cl_khr_fp64, or OpenCL 1.2's optional doubles)
    cl_uint floatLanes = 0;  // CL_DEVICE_NATIVE_VECTOR_WIDTH_FLOAT (16: AVX-512 on PoCL)
    bool isPocl() const;
    // Mesa's rusticl (22.3) rejects the unmap of a mapping not made yet (CL_INVALID_VALUE),
    // so a buffer's sync to the host maps it blocking there (Buffer::syncToHost).
    bool mapMustBlock() const;
    std::string typeName() const;
};

// PoCL's CPU device pins its worker threads to the cores when POCL_AFFINITY is 1. Unless
// the user set it, RayDrive sets it before its first OpenCL call when the process may run
// on every online core (pinning goes by core index, so a taskset or cgroup limit keeps it
// off): on the 2-core development machine the SPD scenes' intersect_closest took
// 0.69-1.02 and their frames 0.80-1.02 of their unpinned time at one sample a pixel,
// 0.96-1.00 at nine (benchmarks/README, session 25). listDevices calls it.
void pinPoclThreadsByDefault();
// Whether PoCL pins its threads in this process (POCL_AFFINITY is 1): --stats reports it.
bool poclThreadsPinned();

// All devices of all platforms; an empty list when no ICD or platform is installed.
std::vector<DeviceInfo> listDevices();

// Resolves a user's device choice. `spec` is an index, a case-insensitive substring of the
// device or platform name, or empty (then RAYDRIVE_DEVICE, then the default rule above).
// Throws std::runtime_error naming the available devices when nothing matches.
DeviceInfo selectDevice(const std::string& spec);

}  // namespace rd
