// Errors of CUDA calls become DeviceError messages with the call, the error, the file and the line.
#include "cuda/cuda_check.hpp"
#include "cuda/cuda_discovery.hpp"

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

TEST(CudaCheck, ARuntimeCallAgreesWithDiscovery) {
  // Where discovery found a GPU the runtime counts it; elsewhere (no driver, or no device) the call
  // either fails with a one-line DeviceError naming itself or counts none, never crashes.
  const Discovery discovery = discover_device();
  int count = 0;
  try {
    POSEKIT_CUDA_CHECK(cudaGetDeviceCount(&count));
    if (discovery.device) {
      EXPECT_GT(count, discovery.device->ordinal);
    } else {
      EXPECT_EQ(count, 0) << "the runtime counts a device that discovery did not find: "
                          << discovery.reason;
    }
  } catch (const DeviceError& error) {
    EXPECT_FALSE(discovery.device) << "discovery found a GPU but the runtime call failed: "
                                   << error.what();
    EXPECT_NE(std::string(error.what()).find("cudaGetDeviceCount(&count) failed with cudaError"),
              std::string::npos)
        << error.what();
  }
}

}  // namespace
}  // namespace posekit::cuda
