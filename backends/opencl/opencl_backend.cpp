// Registry entry of the OpenCL backend: available when discovery finds a device with fp64, which is
// then described without building anything; create() builds the program. "auto" probes it only
// where a GPU device node is present: PoCL alone is no reason to start the platforms.
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
  factory.may_have_gpu = detail::gpu_may_be_present;
  return factory;
}

}  // namespace posekit::opencl
