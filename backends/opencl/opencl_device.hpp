// The OpenCL backend as the registry and the tests see it.
#pragma once

#include "device/backend_factory.hpp"

#include <posekit/device.hpp>

#include <cstdint>
#include <memory>

namespace posekit::opencl {

/// The registry entry "opencl": available when an OpenCL device with fp64 is found.
detail::BackendFactory backend_factory();

/// Choices that the registry leaves at their defaults and tests change.
struct OpenClDeviceOptions {
  /// Largest buffer to allocate, in bytes: 0 for the device's CL_DEVICE_MAX_MEM_ALLOC_SIZE, else
  /// at least kMinimumBufferBytes (chunking.hpp) and used where smaller than the device's limit.
  /// A small value makes every operation cut its work into many chunks.
  std::uint64_t max_buffer_bytes = 0;
  /// Doubles per vector in the kernels (2, 4 or 8); 0 chooses from the device's preferred width.
  int vector_width = 0;
};

/// A device on the OpenCL device that discovery chooses (opencl_discovery.hpp), its program built
/// now. Throws DeviceError when there is none or the build fails (with the build log), and
/// ArgumentError for options out of range.
std::unique_ptr<Device> make_opencl_device(const OpenClDeviceOptions& options = {});

}  // namespace posekit::opencl
