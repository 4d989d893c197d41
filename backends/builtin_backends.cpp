// The list of backends compiled into this build, in the registry's order: GPU APIs first, cpu last.
#include "device/backend_factory.hpp"

namespace posekit {
namespace cpu {
detail::BackendFactory backend_factory();
}
#ifdef POSEKIT_WITH_CUDA
namespace cuda {
detail::BackendFactory backend_factory();
}
#endif
#ifdef POSEKIT_WITH_VULKAN
namespace vulkan {
detail::BackendFactory backend_factory();
}
#endif
#ifdef POSEKIT_WITH_OPENCL
namespace opencl {
detail::BackendFactory backend_factory();
}
#endif

namespace detail {
namespace {
// A backend left out of the build reaches no GPU, so "auto" does not ask it for one.
[[maybe_unused]] BackendFactory not_built(const std::string& name, const std::string& reason) {
  return BackendFactory{name, [name, reason] { return not_built_status(name, reason); }, nullptr,
                        [] { return false; }};
}
}  // namespace

std::vector<BackendFactory> builtin_backends() {
  std::vector<BackendFactory> factories;
#ifdef POSEKIT_WITH_CUDA
  factories.push_back(cuda::backend_factory());
#else
  factories.push_back(not_built("cuda", POSEKIT_CUDA_NOT_BUILT_REASON));
#endif
#ifdef POSEKIT_WITH_VULKAN
  factories.push_back(vulkan::backend_factory());
#else
  factories.push_back(not_built("vulkan", POSEKIT_VULKAN_NOT_BUILT_REASON));
#endif
#ifdef POSEKIT_WITH_OPENCL
  factories.push_back(opencl::backend_factory());
#else
  factories.push_back(not_built("opencl", POSEKIT_OPENCL_NOT_BUILT_REASON));
#endif
  factories.push_back(cpu::backend_factory());
  return factories;
}

}  // namespace detail
}  // namespace posekit
