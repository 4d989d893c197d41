// Registry entry of the CUDA backend: available when discovery finds a GPU this build has kernels
// for, which is then described without creating a context; create() checks the kernels. "auto"
// probes it only where an NVIDIA device node says a GPU could answer.
#include "common/discovery_status.hpp"
#include "cuda_device.hpp"
#include "cuda_discovery.hpp"

namespace posekit::cuda {

detail::BackendFactory backend_factory() {
  detail::BackendFactory factory;
  factory.name = "cuda";
  factory.probe = [] {
    return backends::status_from_discovery(
        discover_device(), [](const DiscoveredDevice& device) { return describe(device); });
  };
  factory.create = [] { return make_cuda_device(); };
  factory.may_have_gpu = detail::nvidia_gpu_may_be_present;
  return factory;
}

}  // namespace posekit::cuda
