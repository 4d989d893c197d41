// Registry entry of the Vulkan backend. This version discovers devices only: the compute shaders
// for the three device operations are not part of it, so the backend is reported unavailable.
#include "device/backend_factory.hpp"
#include "vulkan_discovery.hpp"

namespace posekit::vulkan {

detail::BackendFactory backend_factory() {
  detail::BackendFactory factory;
  factory.name = "vulkan";
  factory.probe = [] {
    BackendStatus status;
    status.state = BackendState::unavailable;
    const Discovery discovery = discover_device();
    if (!discovery.device) {
      status.reason = discovery.reason;
    } else {
      status.reason = "found " + discovery.device->device_name + " [" + discovery.device->driver +
                      "] (shaderFloat64), but this build has no compute shaders for the device operations";
    }
    return status;
  };
  return factory;
}

}  // namespace posekit::vulkan
