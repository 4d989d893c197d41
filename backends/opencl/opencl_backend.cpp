// Registry entry of the OpenCL backend: available when discovery finds a device with fp64, which is
// then described without building anything; create() builds the program.
#include "opencl_device.hpp"
#include "opencl_discovery.hpp"

namespace posekit::opencl {

detail::BackendFactory backend_factory() {
  detail::BackendFactory factory;
  factory.name = "opencl";
  factory.probe = [] {
    BackendStatus status;
    const Discovery discovery = discover_device();
    if (!discovery.device) {
      status.state = BackendState::unavailable;
      status.reason = discovery.reason;
    } else {
      status.state = BackendState::available;
      status.info = describe_device(*discovery.device);
    }
    return status;
  };
  factory.create = [] { return make_opencl_device(); };
  return factory;
}

}  // namespace posekit::opencl
