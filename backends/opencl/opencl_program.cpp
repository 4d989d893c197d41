#include "opencl_program.hpp"

#include "opencl_error.hpp"

#include <posekit/error.hpp>

namespace posekit::opencl {
namespace {

// The log as one line: blank lines dropped, the others joined by " | ".
std::string one_line(const std::string& log) {
  std::string joined;
  std::size_t begin = 0;
  while (begin < log.size()) {
    std::size_t end = log.find('\n', begin);
    if (end == std::string::npos) end = log.size();
    std::string line = log.substr(begin, end - begin);
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ' || line.back() == '\0')) {
      line.pop_back();
    }
    if (!line.empty()) joined += (joined.empty() ? "" : " | ") + line;
    begin = end + 1;
  }
  return joined;
}

}  // namespace

cl::Program build_program(const cl::Context& context, const cl::Device& device,
                          const std::string& source, const std::string& options) {
  cl_int status = CL_SUCCESS;
  cl::Program program(context, source, false, &status);
  POSEKIT_CL_CHECK(status, "clCreateProgramWithSource");
  status = program.build(std::vector<cl::Device>{device}, options.c_str());
  if (status != CL_SUCCESS) {
    std::string log;
    const cl_int log_status = program.getBuildInfo(device, CL_PROGRAM_BUILD_LOG, &log);
    if (log_status != CL_SUCCESS) log = "(no build log: " + status_name(log_status) + ")";
    throw DeviceError("clBuildProgram failed with " + status_name(status) + " (options \"" +
                      options + "\"); build log: " + one_line(log));
  }
  return program;
}

cl::Kernel create_kernel(const cl::Program& program, const char* name) {
  cl_int status = CL_SUCCESS;
  cl::Kernel kernel(program, name, &status);
  POSEKIT_CL_CHECK(status, (std::string("clCreateKernel(") + name + ")").c_str());
  return kernel;
}

}  // namespace posekit::opencl
