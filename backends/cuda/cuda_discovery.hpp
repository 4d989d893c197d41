// Finding a CUDA device, and describing why none was found.
#pragma once

#include <optional>
#include <string>

namespace posekit::cuda {

struct DiscoveredDevice {
  int ordinal = 0;
  std::string device_name;
  std::string driver;  ///< "driver X.Y, runtime A.B, sm_NN"
  int compute_units = 0;
  unsigned long long global_memory_bytes = 0;
};

struct Discovery {
  std::optional<DiscoveredDevice> device;
  std::string reason;  ///< the runtime's error name and text when no device was found
};

/// Asks the CUDA runtime for devices; any error (no driver, insufficient driver, no device) is a
/// reason, never an exception. POSEKIT_CUDA_DEVICE picks an ordinal (default 0).
Discovery discover_device();

}  // namespace posekit::cuda
