// A field uploaded to a CUDA device: its centers and weights as 7 columns (the layout of
// FieldView in cuda_kernels.hpp) followed by the 45 polynomial coefficients, in one allocation.
#pragma once

#include "cuda_buffer.hpp"
#include "cuda_context.hpp"
#include "cuda_kernels.hpp"

#include <posekit/device.hpp>

#include <cstdint>

namespace posekit::cuda {

class CudaField final : public DeviceField {
 public:
  /// Uploads `field` (checked by Device::upload_field). Throws ArgumentError when there are more
  /// centers than a kernel indexes, DeviceError when the device refuses the memory.
  CudaField(const CudaContext& context, const RbfField& field);

  FieldView view() const;

 private:
  DeviceBuffer memory_;
};

}  // namespace posekit::cuda
