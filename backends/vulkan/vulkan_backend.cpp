// Registry entry of the Vulkan backend: available when a physical device with shaderFloat64 (and
// the few other things the shaders need) is found; with POSEKIT_VULKAN_VALIDATION set, also only
// when the validation layer is installed, so that validated runs never go silently unvalidated.
// "auto" probes it only where a GPU device node is present: lavapipe alone is no reason to start it.
#include "common/discovery_status.hpp"
#include "device/backend_factory.hpp"
#include "vulkan_device.hpp"
#include "vulkan_discovery.hpp"
#include "vulkan_validation.hpp"

namespace posekit::vulkan {

detail::BackendFactory backend_factory() {
  detail::BackendFactory factory;
  factory.name = "vulkan";
  factory.probe = [] {
    if (validation_requested() && !validation_layer_installed()) {
      BackendStatus status;
      status.state = BackendState::unavailable;
      status.reason = missing_validation_layer_reason();
      return status;
    }
    return backends::status_from_discovery(
        discover_device(), [](const DiscoveredDevice& device) { return describe(device); });
  };
  factory.create = []() -> std::unique_ptr<Device> {
    return std::make_unique<VulkanDevice>(validation_requested());
  };
  factory.may_have_gpu = detail::gpu_may_be_present;
  return factory;
}

}  // namespace posekit::vulkan
