// What the registry reports for a GPU backend, from its discovery: available with the description
// of the device found, or unavailable with discovery's reason. Nothing is created to find out.
#pragma once

#include <posekit/device_registry.hpp>

namespace posekit::backends {

/// `discovery` has an optional `device` and a `reason`; `describe` turns the device into
/// DeviceInfo.
template <typename Discovery, typename Describe>
BackendStatus status_from_discovery(const Discovery& discovery, Describe describe) {
  BackendStatus status;
  if (!discovery.device) {
    status.state = BackendState::unavailable;
    status.reason = discovery.reason;
  } else {
    status.state = BackendState::available;
    status.info = describe(*discovery.device);
  }
  return status;
}

}  // namespace posekit::backends
