// Registry entry of the CUDA backend: available when discovery finds a GPU this build has kernels
// for, which is then described without creating a context; create() checks the kernels. "auto"
// probes it only where an NVIDIA device node says a GPU could answer.
#include "cuda_device.hpp"
#include "cuda_discovery.hpp"

namespace posekit::cuda {

detail::BackendFactory backend_factory() {
  detail::BackendFactory factory;
  factory.name = "cuda";
  factory.probe = [] {
    BackendStatus status;
    const Discovery discovery = discover_device();
    if (!discovery.device) {
      status.state = BackendState::unavailable;
      status.reason = discovery.reason;
    } else {
      status.state = BackendState::available;
      status.info = describe(*discovery.device);
    }
    return status;
  };
  factory.create = [] { return make_cuda_device(); };
  factory.may_have_gpu = detail::nvidia_gpu_may_be_present;
  return factory;
}

}  // namespace posekit::cuda
