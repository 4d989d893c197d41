// Finding a CUDA GPU: which architectures this build runs on, the fp64 peak a GPU is described
// with, and how the registry reports the backend on this machine, GPU or not.
#include "cuda/cuda_discovery.hpp"
#include "cuda_test_device.hpp"

#include <posekit/device_registry.hpp>
#include <posekit/error.hpp>

#include <gtest/gtest.h>

#include <string>

namespace posekit::cuda {
namespace {

TEST(CudaArchitectures, MachineCodeRunsOnLaterMinorVersionsOfItsMajorOne) {
  const std::string built = "80-real,90-real,90-virtual";
  EXPECT_TRUE(runs_on(built, 8, 0));   // A100
  EXPECT_TRUE(runs_on(built, 8, 6));   // sm_80 code on an RTX A6000
  EXPECT_TRUE(runs_on(built, 8, 9));
  EXPECT_TRUE(runs_on(built, 9, 0));   // H100, H200
  EXPECT_TRUE(runs_on(built, 10, 0));  // B200 through the compute_90 PTX
  EXPECT_TRUE(runs_on(built, 12, 0));
  EXPECT_FALSE(runs_on(built, 7, 0));  // V100: no code for it
  EXPECT_FALSE(runs_on(built, 7, 5));
  EXPECT_FALSE(runs_on("80-real", 9, 0)) << "machine code does not cross major versions";
  EXPECT_TRUE(runs_on("80-virtual", 9, 0));
  EXPECT_TRUE(runs_on("80", 9, 0));
  EXPECT_TRUE(runs_on("80;90", 8, 0)) << "CMake's own separator";
  EXPECT_TRUE(runs_on("90a-real", 9, 0));
  EXPECT_FALSE(runs_on("90a-real", 10, 0)) << "sm_90a code runs on sm_90 only";
  EXPECT_TRUE(runs_on("native", 7, 0)) << "a list it cannot read is not a reason to refuse";
  EXPECT_TRUE(runs_on("", 7, 0));
}

TEST(CudaArchitectures, TheBuildsListIsKnown) {
  EXPECT_FALSE(built_architectures().empty());
}

TEST(CudaPeak, FromMultiprocessorsAndClock) {
  EXPECT_EQ(fp64_fma_per_clock(8, 0), 32);
  EXPECT_EQ(fp64_fma_per_clock(9, 0), 64);
  EXPECT_EQ(fp64_fma_per_clock(8, 6), 2);
  EXPECT_EQ(fp64_fma_per_clock(3, 5), 0) << "unknown";
  DiscoveredDevice h100;
  h100.major = 9;
  h100.minor = 0;
  h100.multiprocessors = 132;
  h100.clock_khz = 1980000;
  // NVIDIA's figure for the H100 SXM: 34 TFLOP/s of fp64 (vector, not tensor cores).
  EXPECT_NEAR(fp64_peak_flops(h100), 33.45e12, 0.01e12);
  const DeviceInfo info = describe(h100);
  EXPECT_NE(info.driver.find("sm_90, 132 SMs at 1980 MHz, fp64 peak 33454 GFLOP/s"),
            std::string::npos)
      << info.driver;
  EXPECT_TRUE(info.fp64);
  EXPECT_FALSE(info.emulated_on_cpu);
  EXPECT_EQ(info.compute_units, 132);
}

TEST(CudaRegistry, ReportsTheBackendWithItsDeviceOrTheReason) {
  const Discovery discovery = discover_device();
  for (const BackendStatus& status : list_backends()) {
    if (status.name != "cuda") continue;
    if (!discovery.device) {
      EXPECT_EQ(status.state, BackendState::unavailable);
      EXPECT_EQ(status.reason, discovery.reason);
      EXPECT_FALSE(status.reason.empty());
      EXPECT_EQ(status.reason.find('\n'), std::string::npos) << status.reason;
      try {
        create_device("cuda");
        ADD_FAILURE() << "create_device(\"cuda\") succeeded without a device";
      } catch (const Error& error) {
        EXPECT_NE(std::string(error.what()).find(discovery.reason), std::string::npos)
            << error.what();
      }
      EXPECT_THROW(make_cuda_device(), DeviceError);
    } else {
      EXPECT_EQ(status.state, BackendState::available) << status.reason;
      EXPECT_EQ(status.info.backend, "cuda");
      EXPECT_EQ(status.info.name, discovery.device->device_name);
      EXPECT_TRUE(status.info.fp64);
      EXPECT_EQ(status.info.compute_units, discovery.device->multiprocessors);
      EXPECT_EQ(status.info.max_buffer_bytes, discovery.device->global_memory_bytes);
    }
    return;
  }
  ADD_FAILURE() << "the registry does not list cuda";
}

TEST(CudaRegistry, WithoutADriverTheReasonIsTheRuntimes) {
  const Discovery discovery = discover_device();
  if (discovery.device) GTEST_SKIP() << "a CUDA device is present: " << discovery.device->device_name;
  // No driver, an old driver, no GPU: whichever, the reason comes from the runtime.
  const bool runtime_said_so = discovery.reason.rfind("cudaGetDeviceCount failed (cudaError", 0) == 0 ||
                               discovery.reason == "no CUDA device found" ||
                               discovery.reason.find("this build has CUDA kernels for") !=
                                   std::string::npos;
  EXPECT_TRUE(runtime_said_so) << discovery.reason;
}

TEST(CudaDeviceOptions, RejectsABudgetBelowTheMinimum) {
  CudaDeviceOptions options;
  options.max_chunk_bytes = 100;
  try {
    make_cuda_device(options);
    ADD_FAILURE() << "no ArgumentError";
  } catch (const ArgumentError& error) {
    EXPECT_NE(std::string(error.what()).find("max_chunk_bytes"), std::string::npos);
  }
}

}  // namespace
}  // namespace posekit::cuda
