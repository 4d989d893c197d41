// Registry entry of the OpenCL backend. This version discovers devices only: the OpenCL kernels for
// the three device operations are not part of it, so the backend is reported unavailable.
#include "device/backend_factory.hpp"
#include "opencl_discovery.hpp"

namespace posekit::opencl {

detail::BackendFactory backend_factory() {
  detail::BackendFactory factory;
  factory.name = "opencl";
  factory.probe = [] {
    BackendStatus status;
    status.state = BackendState::unavailable;
    const Discovery discovery = discover_device();
    if (!discovery.device) {
      status.reason = discovery.reason;
    } else {
      status.reason = "found " + discovery.device->device_name + " on " + discovery.device->platform_name +
                      " (fp64), but this build has no OpenCL kernels for the device operations";
    }
    return status;
  };
  return factory;
}

}  // namespace posekit::opencl
