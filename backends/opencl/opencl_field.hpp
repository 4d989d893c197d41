// A field uploaded to an OpenCL device: its centers and weights in one or more parts (a part per
// buffer the device allows), and its polynomial.
#pragma once

#include "opencl_runtime.hpp"

#include <posekit/device.hpp>

#include <vector>

namespace posekit::opencl {

class OpenClField final : public DeviceField {
 public:
  /// Centers and weights of one buffer: seven columns of `stride` doubles (center x, y, z, t,
  /// weight x, y, z), the layout of kernels/opencl/rbf_field.cl; stride is a multiple of the vector
  /// width and the columns are zero beyond `count`.
  struct Part {
    cl::Buffer buffer;
    int count = 0;
    int stride = 0;
  };

  /// Uploads `field` (checked by Device::upload_field). Throws DeviceError when the device
  /// refuses a buffer.
  OpenClField(const OpenClRuntime& runtime, const RbfField& field);

  /// At least one part; a field of no centers has one empty part.
  const std::vector<Part>& parts() const { return parts_; }
  /// 45 doubles: the 15 by 3 polynomial, column-major.
  const cl::Buffer& polynomial() const { return polynomial_; }

 private:
  std::vector<Part> parts_;
  cl::Buffer polynomial_;
};

}  // namespace posekit::opencl
