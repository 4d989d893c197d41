// Finding a Vulkan 1.2 physical device that can run posekit's compute shaders (shaderFloat64
// above all), and describing why none was found.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <optional>
#include <string>

namespace posekit::vulkan {

struct DiscoveredDevice {
  std::string device_name;
  std::string driver;   ///< driver name and info, e.g. "llvmpipe (Mesa 22.3.6 (LLVM 15.0.6))"
  bool is_cpu = false;  ///< a CPU implementation (lavapipe, SwiftShader)
  std::uint64_t max_storage_buffer_bytes = 0;
  /// lavapipe: loops of a shader invocation stop after 65,535 iterations in all (loop_budget.hpp).
  bool loop_limited = false;
};

/// A physical device of a live instance that meets every requirement.
struct PhysicalDeviceChoice {
  VkPhysicalDevice handle = VK_NULL_HANDLE;
  std::uint32_t compute_queue_family = 0;
  DiscoveredDevice description;
};

struct Discovery {
  std::optional<DiscoveredDevice> device;
  std::string reason;  ///< why no device was chosen
};

/// Looks at every physical device of `instance` and picks one that has Vulkan 1.2, shaderFloat64,
/// dynamic indexing of uniform-buffer arrays, a compute queue, subgroup votes in compute shaders
/// and 64 KiB uniform buffers,
/// preferring a discrete GPU, then an integrated one, then anything but a CPU implementation.
/// POSEKIT_VULKAN_DEVICE (a substring of the device name) restricts the search. Returns nullopt
/// and sets `reason` (naming each device and what it lacks) when none qualifies. Never throws.
std::optional<PhysicalDeviceChoice> choose_physical_device(VkInstance instance,
                                                           std::string& reason);

/// The same choice on a temporary instance: what the registry reports. Never throws.
Discovery discover_device();

}  // namespace posekit::vulkan
