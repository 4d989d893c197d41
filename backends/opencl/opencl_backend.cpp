// Registry entry of the OpenCL backend: available when discovery finds a device with fp64, which is
// then described without building anything; create() builds the program. "auto" probes it only
// where a GPU device node is present: PoCL alone is no reason to start the platforms.
#include "common/discovery_status.hpp"
#include "opencl_device.hpp"
#include "opencl_discovery.hpp"

namespace posekit::opencl {

detail::BackendFactory backend_factory() {
  detail::BackendFactory factory;
  factory.name = "opencl";
  factory.probe = [] {
    return backends::status_from_discovery(
        discover_device(), [](const DiscoveredDevice& device) { return describe_device(device); });
  };
  factory.create = [] { return make_opencl_device(); };
  factory.may_have_gpu = detail::gpu_may_be_present;
  return factory;
}

}  // namespace posekit::opencl
