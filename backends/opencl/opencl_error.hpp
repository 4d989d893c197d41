// OpenCL status codes turned into DeviceError messages that name the call, file and line.
#pragma once

#include <CL/opencl.hpp>

#include <string>

namespace posekit::opencl {

/// "CL_OUT_OF_RESOURCES" and the like; the number for a code this list does not know.
std::string status_name(cl_int status);

/// Throws DeviceError("CALL failed with NAME (CODE) at FILE:LINE") unless status is CL_SUCCESS.
void check(cl_int status, const char* call, const char* file, int line);

}  // namespace posekit::opencl

/// Checks the cl_int returned by an OpenCL call; `call` names it ("clEnqueueNDRangeKernel").
#define POSEKIT_CL_CHECK(status, call) ::posekit::opencl::check((status), (call), __FILE__, __LINE__)
