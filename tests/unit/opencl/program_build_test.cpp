// Building programs: the embedded program builds, and a program that does not compile is reported
// as a DeviceError carrying the compiler's log on one line.
#include "opencl/opencl_program.hpp"
#include "opencl/opencl_program_source.hpp"
#include "opencl_test_device.hpp"

#include <posekit/error.hpp>

#include <gtest/gtest.h>

#include <cstring>
#include <string>

namespace posekit::opencl {
namespace {

struct Target {
  cl::Device device;
  cl::Context context;
};

Target target() {
  const Discovery discovery = discover_device();
  Target found;
  found.device = discovery.device->device;
  found.context = cl::Context(found.device);
  return found;
}

TEST(ProgramBuild, EmbeddedProgramHoldsTheSharedMathAndEveryKernel) {
  const std::string source = program_source();
  for (const char* part : {"POSEKIT_KERNEL_MATH_H", "PK_RK45_INTEGRATE_PARTICLE", "pk_log_vec",
                           "__kernel void pk_rbf_assemble", "__kernel void pk_rbf_evaluate",
                           "__kernel void pk_rk45_integrate"}) {
    EXPECT_NE(source.find(part), std::string::npos) << part;
  }
}

TEST(ProgramBuild, FailureCarriesTheBuildLogOnOneLine) {
  POSEKIT_REQUIRE_OPENCL();
  const Target found = target();
  const std::string broken =
      "__kernel void broken(__global double* out) {\n"
      "  out[0] = posekit_undeclared_name;\n"
      "}\n";
  try {
    build_program(found.context, found.device, broken, "-cl-std=CL1.2");
    ADD_FAILURE() << "a program with an undeclared name was built";
  } catch (const DeviceError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("clBuildProgram"), std::string::npos) << message;
    EXPECT_NE(message.find("build log"), std::string::npos) << message;
    EXPECT_NE(message.find("posekit_undeclared_name"), std::string::npos)
        << "the compiler's complaint should be in the message: " << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

TEST(ProgramBuild, MissingKernelIsNamed) {
  POSEKIT_REQUIRE_OPENCL();
  const Target found = target();
  const cl::Program program =
      build_program(found.context, found.device, "__kernel void present(void) {}", "");
  try {
    create_kernel(program, "absent_kernel");
    ADD_FAILURE() << "created a kernel the program does not have";
  } catch (const DeviceError& error) {
    EXPECT_NE(std::string(error.what()).find("absent_kernel"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace posekit::opencl
