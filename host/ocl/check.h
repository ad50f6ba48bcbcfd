// check.h: every OpenCL call goes through RD_CL_CHECK, which throws ClError naming the call,
// the error (by name, not just number) and the device, as the user's bug report needs.
#pragma once
#include <stdexcept>
#include <string>

#include "cl_api.h"

namespace rd {

const char* clErrorName(cl_int code);

class ClError : public std::runtime_error {
public:
    ClError(const std::string& call, cl_int code, const std::string& device);
    cl_int code() const { return m_code; }

private:
    cl_int m_code;
};

// Throws ClError when `code` is not CL_SUCCESS.
void clCheck(cl_int code, const char* call, const std::string& device);

}  // namespace rd

#define RD_CL_CHECK(call, device) ::rd::clCheck((call), #call, (device))
