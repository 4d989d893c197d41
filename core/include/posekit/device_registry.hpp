// The registry of compute backends: which are built, which can run here, and why not.
#pragma once

#include <posekit/device.hpp>

#include <memory>
#include <string>
#include <vector>

namespace posekit {

enum class BackendState { available, unavailable, not_built };

/// One backend as the registry sees it on this machine.
struct BackendStatus {
  std::string name;      ///< "cuda", "vulkan", "opencl" or "cpu"
  BackendState state = BackendState::not_built;
  std::string reason;    ///< why it is unavailable or not built; empty when available
  DeviceInfo info;       ///< filled when available
};

/// Backend names from a comma-separated list such as "cpu, opencl" (blanks trimmed, empty names dropped).
std::vector<std::string> parse_backend_list(const std::string& comma_separated);

/// Returns "available", "unavailable" or "not built".
const char* to_string(BackendState state);

/// Probes every backend, in registration order (GPU backends first, cpu last). Never throws:
/// a missing driver or device is reported as unavailable with the reason.
/// Backends named in the environment variable POSEKIT_DISABLE_BACKENDS (comma-separated)
/// are reported unavailable.
std::vector<BackendStatus> list_backends();

/// Creates a device of the named backend ("cpu", "opencl", "vulkan", "cuda"), or with "auto"
/// the fastest available one (a real GPU first, then the CPU backend, then CPU emulations).
/// Throws ArgumentError for an unknown name and Error with the reason for an unavailable one.
std::unique_ptr<Device> create_device(const std::string& name = "auto");

}  // namespace posekit
