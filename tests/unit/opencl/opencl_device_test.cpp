// The OpenCL device as the registry shows it, and the options of make_opencl_device.
#include "opencl_test_device.hpp"

#include <posekit/device_registry.hpp>
#include <posekit/error.hpp>

#include <gtest/gtest.h>

#include <string>

namespace posekit::opencl {
namespace {

TEST(OpenClDevice, RegistryListsItWithPlatformAndDevice) {
  POSEKIT_REQUIRE_OPENCL();
  const Discovery discovery = discover_device();
  for (const BackendStatus& status : list_backends()) {
    if (status.name != "opencl") continue;
    ASSERT_EQ(status.state, BackendState::available) << status.reason;
    EXPECT_TRUE(status.reason.empty());
    EXPECT_EQ(status.info.backend, "opencl");
    EXPECT_EQ(status.info.name, discovery.device->device_name);
    EXPECT_NE(status.info.driver.find(discovery.device->platform_name), std::string::npos)
        << status.info.driver;
    EXPECT_TRUE(status.info.fp64);
    EXPECT_EQ(status.info.emulated_on_cpu, discovery.device->is_cpu);
    EXPECT_EQ(status.info.max_buffer_bytes, discovery.device->max_allocation_bytes);
    EXPECT_GE(status.info.compute_units, 1);
    return;
  }
  ADD_FAILURE() << "the registry does not list opencl";
}

TEST(OpenClDevice, PoclIsACpuEmulation) {
  POSEKIT_REQUIRE_OPENCL();
  const Discovery discovery = discover_device();
  if (discovery.device->platform_name.find("Portable Computing Language") == std::string::npos) {
    GTEST_SKIP() << "the device is not PoCL's: " << discovery.device->platform_name;
  }
  EXPECT_TRUE(create_device("opencl")->info().emulated_on_cpu);
}

TEST(OpenClDevice, CreatedByName) {
  POSEKIT_REQUIRE_OPENCL();
  const std::unique_ptr<Device> device = create_device("opencl");
  EXPECT_EQ(device->info().backend, "opencl");
}

TEST(OpenClDevice, RejectsOptionsOutOfRange) {
  OpenClDeviceOptions small;
  small.max_buffer_bytes = 100;
  EXPECT_THROW(
      {
        try {
          make_opencl_device(small);
        } catch (const ArgumentError& error) {
          EXPECT_NE(std::string(error.what()).find("max_buffer_bytes"), std::string::npos);
          throw;
        }
      },
      ArgumentError);
  OpenClDeviceOptions odd;
  odd.vector_width = 3;
  EXPECT_THROW(
      {
        try {
          make_opencl_device(odd);
        } catch (const ArgumentError& error) {
          EXPECT_NE(std::string(error.what()).find("vector_width"), std::string::npos);
          throw;
        }
      },
      ArgumentError);
}

}  // namespace
}  // namespace posekit::opencl
