// How a backend plugs into the registry: a probe that never throws, a constructor, and for GPU APIs
// a presence check that lets "auto" skip starting an API that has no GPU to find.
#pragma once

#include <posekit/device_registry.hpp>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace posekit::detail {

struct BackendFactory {
  std::string name;
  /// Reports the state on this machine; must not throw.
  std::function<BackendStatus()> probe;
  /// Creates the device; called only when probe() said available. May throw Error.
  std::function<std::unique_ptr<Device>()> create;
  /// Whether probe() could find a real GPU here, judged without starting the API (from device
  /// nodes, in microseconds); must not throw. "auto" probes a GPU API only when this says yes, or
  /// when it is empty; the cpu backend leaves it empty (it is not asked).
  std::function<bool()> may_have_gpu;
};

/// Whether CUDA could reach a GPU here: an NVIDIA device node (/dev/nvidiactl, /dev/nvidia0), the
/// NVIDIA kernel module's list of GPUs (the driver creates missing nodes on first use) or WSL's GPU
/// node /dev/dxg. Looks at the file system only; true where it cannot tell (not Linux).
bool nvidia_gpu_may_be_present() noexcept;

/// Whether Vulkan or OpenCL could reach a real GPU here: a DRM render node (/dev/dri/renderD*), a
/// vendor's compute node (NVIDIA's as above, AMD's /dev/kfd, ARM Mali's, Qualcomm Adreno's) or WSL's
/// /dev/dxg. CPU emulations (lavapipe, PoCL) need none of them. True where it cannot tell (not Linux).
bool gpu_may_be_present() noexcept;

/// Every backend known to this build, GPU backends first and cpu last (backends/builtin_backends.cpp).
std::vector<BackendFactory> builtin_backends();

/// create_device() over the given factories instead of the built-in ones.
std::unique_ptr<Device> create_device(const std::vector<BackendFactory>& factories, const std::string& name);

/// Status of a backend that this build does not contain.
BackendStatus not_built_status(const std::string& name, const std::string& reason);

}  // namespace posekit::detail
