// Building an OpenCL program for one device, with the compiler's log in the error.
#pragma once

#include <CL/opencl.hpp>

#include <string>

namespace posekit::opencl {

/// Compiles and links `source` for `device` with the compiler `options`. Throws DeviceError when
/// the build fails; its message holds the device's build log (lines joined by " | ", so that the
/// message stays one line).
cl::Program build_program(const cl::Context& context, const cl::Device& device,
                          const std::string& source, const std::string& options);

/// Creates kernel `name` of a built program; throws DeviceError naming it when that fails.
cl::Kernel create_kernel(const cl::Program& program, const char* name);

}  // namespace posekit::opencl
