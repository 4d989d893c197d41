// Finding an OpenCL device with double precision, and describing why none was found.
#pragma once

#include <CL/opencl.hpp>

#include <optional>
#include <string>

namespace posekit::opencl {

struct DiscoveredDevice {
  cl::Platform platform;
  cl::Device device;
  std::string platform_name;  ///< platform name and version
  std::string device_name;
  bool is_cpu = false;
  std::uint64_t max_allocation_bytes = 0;
  int compute_units = 0;
};

struct Discovery {
  std::optional<DiscoveredDevice> device;  ///< the chosen fp64 device, if any
  std::string reason;                      ///< why none was chosen
};

/// Looks at every platform and device; prefers a GPU with fp64 over a CPU device with fp64.
/// POSEKIT_OPENCL_PLATFORM (a substring of the platform name) restricts the search. Never throws.
Discovery discover_device();

}  // namespace posekit::opencl
