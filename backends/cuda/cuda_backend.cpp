// Registry entry of the CUDA backend. This version discovers devices only: the CUDA kernels for the
// three device operations are not part of it, so the backend is reported unavailable.
#include "cuda_discovery.hpp"
#include "device/backend_factory.hpp"

namespace posekit::cuda {

detail::BackendFactory backend_factory() {
  detail::BackendFactory factory;
  factory.name = "cuda";
  factory.probe = [] {
    BackendStatus status;
    status.state = BackendState::unavailable;
    const Discovery discovery = discover_device();
    if (!discovery.device) {
      status.reason = discovery.reason;
    } else {
      status.reason = "found " + discovery.device->device_name + " [" + discovery.device->driver +
                      "], but this build has no CUDA kernels for the device operations";
    }
    return status;
  };
  return factory;
}

}  // namespace posekit::cuda
