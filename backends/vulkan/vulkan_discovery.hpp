// Finding a Vulkan 1.2 physical device with shaderFloat64, and describing why none was found.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace posekit::vulkan {

struct DiscoveredDevice {
  std::string device_name;
  std::string driver;  ///< driver name and info, e.g. "llvmpipe (Mesa 22.3.6)"
  bool is_cpu = false;
  std::uint64_t max_storage_buffer_bytes = 0;
};

struct Discovery {
  std::optional<DiscoveredDevice> device;
  std::string reason;  ///< why no device was chosen
};

/// Creates a temporary instance and looks at every physical device; prefers a GPU with
/// shaderFloat64 over a CPU implementation. POSEKIT_VULKAN_DEVICE (a substring of the device
/// name) restricts the search. Never throws.
Discovery discover_device();

}  // namespace posekit::vulkan
