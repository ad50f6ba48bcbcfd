// device.cpp: enumerating OpenCL platforms and devices and matching a user's choice.
#include "device.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#ifdef __linux__
#include <sched.h>
#include <unistd.h>
#endif

#include "check.h"

namespace rd {
namespace {

std::string platformString(cl_platform_id p, cl_platform_info what) {
    size_t n = 0;
    if (clGetPlatformInfo(p, what, 0, nullptr, &n) != CL_SUCCESS || n == 0) return {};
    std::string s(n, '\0');
    clGetPlatformInfo(p, what, n, s.data(), nullptr);
    s.resize(std::strlen(s.c_str()));
    return s;
}

std::string deviceString(cl_device_id d, cl_device_info what) {
    size_t n = 0;
    if (clGetDeviceInfo(d, what, 0, nullptr, &n) != CL_SUCCESS || n == 0) return {};
    std::string s(n, '\0');
    clGetDeviceInfo(d, what, n, s.data(), nullptr);
    s.resize(std::strlen(s.c_str()));
    return s;
}

template <typename T>
T deviceValue(cl_device_id d, cl_device_info what) {
    T v{};
    clGetDeviceInfo(d, what, sizeof(T), &v, nullptr);
    return v;
}

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
}

}  // namespace

bool DeviceInfo::isPocl() const {
    return platformName.find("Portable Computing Language") != std::string::npos;
}

bool DeviceInfo::mapMustBlock() const { return platformName == "rusticl"; }

std::string DeviceInfo::typeName() const {
    if (type & CL_DEVICE_TYPE_GPU) return "GPU";
    if (type & CL_DEVICE_TYPE_CPU) return "CPU";
    if (type & CL_DEVICE_TYPE_ACCELERATOR) return "accelerator";
    return "other";
}

void pinPoclThreadsByDefault() {
#ifdef __linux__
    if (std::getenv("POCL_AFFINITY")) return;  // the user's choice (or an earlier call's)
    cpu_set_t allowed;
    CPU_ZERO(&allowed);
    const long online = sysconf(_SC_NPROCESSORS_ONLN);
    if (sched_getaffinity(0, sizeof allowed, &allowed) == 0 && online > 0 &&
        CPU_COUNT(&allowed) == online)
        setenv("POCL_AFFINITY", "1", 0);
#endif
}

bool poclThreadsPinned() {
    const char* v = std::getenv("POCL_AFFINITY");
    return v && std::atoi(v) == 1;
}

std::vector<DeviceInfo> listDevices() {
    pinPoclThreadsByDefault();  // (before the first OpenCL call: PoCL reads it then)
    cl_uint np = 0;
    if (clGetPlatformIDs(0, nullptr, &np) != CL_SUCCESS || np == 0) return {};
    std::vector<cl_platform_id> platforms(np);
    RD_CL_CHECK(clGetPlatformIDs(np, platforms.data(), nullptr), "");
    std::vector<DeviceInfo> out;
    for (cl_platform_id p : platforms) {
        cl_uint nd = 0;
        if (clGetDeviceIDs(p, CL_DEVICE_TYPE_ALL, 0, nullptr, &nd) != CL_SUCCESS) continue;
        std::vector<cl_device_id> devs(nd);
        if (clGetDeviceIDs(p, CL_DEVICE_TYPE_ALL, nd, devs.data(), nullptr) != CL_SUCCESS)
            continue;
        for (cl_device_id d : devs) {
            DeviceInfo info;
            info.index = static_cast<int>(out.size());
            info.platform = p;
            info.device = d;
            info.platformName = platformString(p, CL_PLATFORM_NAME);
            info.name = deviceString(d, CL_DEVICE_NAME);
            info.vendor = deviceString(d, CL_DEVICE_VENDOR);
            info.version = deviceString(d, CL_DEVICE_VERSION);
            info.driverVersion = deviceString(d, CL_DRIVER_VERSION);
            info.type = deviceValue<cl_device_type>(d, CL_DEVICE_TYPE);
            info.computeUnits = deviceValue<cl_uint>(d, CL_DEVICE_MAX_COMPUTE_UNITS);
            info.globalMemBytes = deviceValue<cl_ulong>(d, CL_DEVICE_GLOBAL_MEM_SIZE);
            info.maxAllocBytes = deviceValue<cl_ulong>(d, CL_DEVICE_MAX_MEM_ALLOC_SIZE);
            info.maxWorkGroupSize = deviceValue<size_t>(d, CL_DEVICE_MAX_WORK_GROUP_SIZE);
            info.fp64 = deviceValue<cl_device_fp_config>(d, CL_DEVICE_DOUBLE_FP_CONFIG) != 0;
            info.floatLanes = deviceValue<cl_uint>(d, CL_DEVICE_NATIVE_VECTOR_WIDTH_FLOAT);
            out.push_back(info);
        }
    }
    return out;
}

DeviceInfo selectDevice(const std::string& specIn) {
    std::string spec = specIn;
    if (spec.empty()) {
        const char* env = std::getenv("RAYDRIVE_DEVICE");
        if (env) spec = env;
    }
    std::vector<DeviceInfo> devices = listDevices();
    if (devices.empty())
        throw std::runtime_error(
            "no OpenCL device found: install an OpenCL driver (e.g. apt-get install "
            "pocl-opencl-icd) and check `clinfo -l`");
    auto available = [&] {
        std::string s;
        for (const DeviceInfo& d : devices)
            s += "\n  " + std::to_string(d.index) + ": " + d.name + " (" + d.platformName + ")";
        return s;
    };
    if (spec.empty()) {
        for (const DeviceInfo& d : devices)
            if (d.isPocl() && (d.type & CL_DEVICE_TYPE_CPU)) return d;
        for (const DeviceInfo& d : devices)
            if (d.type & CL_DEVICE_TYPE_GPU) return d;
        return devices.front();
    }
    bool numeric = !spec.empty() && std::all_of(spec.begin(), spec.end(), [](char c) {
        return std::isdigit(static_cast<unsigned char>(c));
    });
    if (numeric) {
        long idx = std::strtol(spec.c_str(), nullptr, 10);
        if (idx >= 0 && idx < static_cast<long>(devices.size())) return devices[idx];
        throw std::runtime_error("no OpenCL device with index " + spec + "; available:" +
                                 available());
    }
    std::string needle = lower(spec);
    for (const DeviceInfo& d : devices)
        if (lower(d.name).find(needle) != std::string::npos ||
            lower(d.platformName).find(needle) != std::string::npos)
            return d;
    throw std::runtime_error("no OpenCL device matches '" + spec + "'; available:" +
                             available());
}

}  // namespace rd
