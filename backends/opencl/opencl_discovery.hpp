// Finding an OpenCL device with double precision, and describing why none was found.
#pragma once

#include <posekit/device.hpp>

#include <CL/opencl.hpp>

#include <cstdint>
#include <optional>
#include <string>

namespace posekit::opencl {

struct DiscoveredDevice {
  cl::Platform platform;
  cl::Device device;
  std::string platform_name;  ///< platform name and version
  std::string device_name;
  std::string driver_version;  ///< CL_DRIVER_VERSION
  bool is_cpu = false;
  std::uint64_t max_allocation_bytes = 0;
  int compute_units = 0;
};

struct Discovery {
  std::optional<DiscoveredDevice> device;  ///< the chosen fp64 device, if any
  std::string reason;                      ///< why none was chosen
};

/// Looks at every platform and device; prefers a GPU with fp64 over a CPU device with fp64 and
/// skips devices that are not available or have no compiler. POSEKIT_OPENCL_PLATFORM (a substring
/// of the platform name) restricts the search. Prepares the runtime's environment first
/// (pocl_cache.hpp). Never throws.
Discovery discover_device();

/// The registry's description: the device's name, the platform and driver, fp64, whether it is a
/// CPU device (PoCL's pthread device is), the largest buffer and the compute units.
DeviceInfo describe_device(const DiscoveredDevice& device);

}  // namespace posekit::opencl
