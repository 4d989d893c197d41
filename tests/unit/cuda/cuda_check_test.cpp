// Errors of CUDA calls become DeviceError messages with the call, the error, the file and the line.
#include "cuda/cuda_check.hpp"

#include <posekit/error.hpp>

#include <gtest/gtest.h>

#include <string>

namespace posekit::cuda {
namespace {

TEST(CudaCheck, SuccessPassesSilently) { EXPECT_NO_THROW(POSEKIT_CUDA_CHECK(cudaSuccess)); }

TEST(CudaCheck, AnErrorNamesTheCallTheErrorAndThePlace) {
  const int line = __LINE__ + 2;
  try {
    POSEKIT_CUDA_CHECK(cudaErrorMemoryAllocation);
    ADD_FAILURE() << "no DeviceError";
  } catch (const DeviceError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("cudaErrorMemoryAllocation failed with cudaErrorMemoryAllocation: "),
              std::string::npos)
        << message;
    EXPECT_NE(message.find("cuda_check_test.cpp:" + std::to_string(line)), std::string::npos)
        << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

TEST(CudaCheck, ARuntimeCallWithoutADriverFailsCleanly) {
  // On a machine without a (recent enough) driver every call fails; with one this allocation of
  // nothing succeeds. Either way the outcome is a value or a DeviceError, never a crash.
  int count = 0;
  try {
    POSEKIT_CUDA_CHECK(cudaGetDeviceCount(&count));
    EXPECT_GE(count, 0);
  } catch (const DeviceError& error) {
    EXPECT_NE(std::string(error.what()).find("cudaGetDeviceCount(&count) failed with cudaError"),
              std::string::npos)
        << error.what();
  }
}

}  // namespace
}  // namespace posekit::cuda
