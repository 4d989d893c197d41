// Helpers of the Vulkan backend's own tests: validated devices and a runner for the probe shader
// shaders/kernel_math_probe.comp.
#pragma once

#include "vulkan/vulkan_device.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace posekit::vulkan::testing {

/// A Vulkan device with the validation layer on (a missing layer throws DeviceError, failing the
/// test), or nullptr with `reason` when this machine has no usable Vulkan device.
std::unique_ptr<VulkanDevice> make_validated_device(std::string& reason, DeviceTuning tuning = {});

/// Modes of kernel_math_probe.comp.
enum class Probe : std::uint32_t { log = 0, pow_error_exponent = 1, constants = 2 };

/// Runs the probe shader on `device` with one invocation per input; returns one output each.
std::vector<double> run_probe(const VulkanDevice& device, Probe probe,
                              const std::vector<double>& inputs);

}  // namespace posekit::vulkan::testing

// Declares `std::unique_ptr<VulkanDevice> name` or skips the test with the reason.
#define POSEKIT_VALIDATED_VULKAN_DEVICE_OR_SKIP(name, ...)                             \
  std::string name##_reason;                                                           \
  const std::unique_ptr<::posekit::vulkan::VulkanDevice> name =                        \
      ::posekit::vulkan::testing::make_validated_device(name##_reason, ##__VA_ARGS__); \
  if (!(name)) GTEST_SKIP() << name##_reason
