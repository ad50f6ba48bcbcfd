// check.cpp: OpenCL error names and the ClError exception.
#include "check.h"

namespace rd {

const char* clErrorName(cl_int code) {
    switch (code) {
#define RD_CASE(x) \
    case x:        \
        return #x;
        RD_CASE(CL_SUCCESS)
        RD_CASE(CL_DEVICE_NOT_FOUND)
        RD_CASE(CL_DEVICE_NOT_AVAILABLE)
        RD_CASE(CL_COMPILER_NOT_AVAILABLE)
        RD_CASE(CL_MEM_OBJECT_ALLOCATION_FAILURE)
        RD_CASE(CL_OUT_OF_RESOURCES)
        RD_CASE(CL_OUT_OF_HOST_MEMORY)
        RD_CASE(CL_PROFILING_INFO_NOT_AVAILABLE)
        RD_CASE(CL_MEM_COPY_OVERLAP)
        RD_CASE(CL_IMAGE_FORMAT_MISMATCH)
        RD_CASE(CL_IMAGE_FORMAT_NOT_SUPPORTED)
        RD_CASE(CL_BUILD_PROGRAM_FAILURE)
        RD_CASE(CL_MAP_FAILURE)
        RD_CASE(CL_MISALIGNED_SUB_BUFFER_OFFSET)
        RD_CASE(CL_EXEC_STATUS_ERROR_FOR_EVENTS_IN_WAIT_LIST)
        RD_CASE(CL_COMPILE_PROGRAM_FAILURE)
        RD_CASE(CL_LINKER_NOT_AVAILABLE)
        RD_CASE(CL_LINK_PROGRAM_FAILURE)
        RD_CASE(CL_DEVICE_PARTITION_FAILED)
        RD_CASE(CL_KERNEL_ARG_INFO_NOT_AVAILABLE)
        RD_CASE(CL_INVALID_VALUE)
        RD_CASE(CL_INVALID_DEVICE_TYPE)
        RD_CASE(CL_INVALID_PLATFORM)
        RD_CASE(CL_INVALID_DEVICE)
        RD_CASE(CL_INVALID_CONTEXT)
        RD_CASE(CL_INVALID_QUEUE_PROPERTIES)
        RD_CASE(CL_INVALID_COMMAND_QUEUE)
        RD_CASE(CL_INVALID_HOST_PTR)
        RD_CASE(CL_INVALID_MEM_OBJECT)
        RD_CASE(CL_INVALID_IMAGE_FORMAT_DESCRIPTOR)
        RD_CASE(CL_INVALID_IMAGE_SIZE)
        RD_CASE(CL_INVALID_SAMPLER)
        RD_CASE(CL_INVALID_BINARY)
        RD_CASE(CL_INVALID_BUILD_OPTIONS)
        RD_CASE(CL_INVALID_PROGRAM)
        RD_CASE(CL_INVALID_PROGRAM_EXECUTABLE)
        RD_CASE(CL_INVALID_KERNEL_NAME)
        RD_CASE(CL_INVALID_KERNEL_DEFINITION)
        RD_CASE(CL_INVALID_KERNEL)
        RD_CASE(CL_INVALID_ARG_INDEX)
        RD_CASE(CL_INVALID_ARG_VALUE)
        RD_CASE(CL_INVALID_ARG_SIZE)
        RD_CASE(CL_INVALID_KERNEL_ARGS)
        RD_CASE(CL_INVALID_WORK_DIMENSION)
        RD_CASE(CL_INVALID_WORK_GROUP_SIZE)
        RD_CASE(CL_INVALID_WORK_ITEM_SIZE)
        RD_CASE(CL_INVALID_GLOBAL_OFFSET)
        RD_CASE(CL_INVALID_EVENT_WAIT_LIST)
        RD_CASE(CL_INVALID_EVENT)
        RD_CASE(CL_INVALID_OPERATION)
        RD_CASE(CL_INVALID_GL_OBJECT)
        RD_CASE(CL_INVALID_BUFFER_SIZE)
        RD_CASE(CL_INVALID_MIP_LEVEL)
        RD_CASE(CL_INVALID_GLOBAL_WORK_SIZE)
        RD_CASE(CL_INVALID_PROPERTY)
        RD_CASE(CL_INVALID_IMAGE_DESCRIPTOR)
        RD_CASE(CL_INVALID_COMPILER_OPTIONS)
        RD_CASE(CL_INVALID_LINKER_OPTIONS)
        RD_CASE(CL_INVALID_DEVICE_PARTITION_COUNT)
#undef RD_CASE
        case -1001:
            return "CL_PLATFORM_NOT_FOUND_KHR (no OpenCL platform: is an ICD installed?)";
        default:
            return "unknown OpenCL error";
    }
}

ClError::ClError(const std::string& call, cl_int code, const std::string& device)
    : std::runtime_error("OpenCL error in " + call + ": " + clErrorName(code) + " (" +
                         std::to_string(code) + ")" +
                         (device.empty() ? std::string() : " on device '" + device + "'")),
      m_code(code) {}

void clCheck(cl_int code, const char* call, const std::string& device) {
    if (code != CL_SUCCESS) throw ClError(call, code, device);
}

}  // namespace rd
