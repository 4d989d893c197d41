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
  /// Uploads `field`. Throws ArgumentError when the weights do not have one row per center or
  /// there are more centers than a kernel indexes, DeviceError when the device refuses the memory.
  CudaField(const CudaContext& context, const RbfField& field);

  int center_count() const override { return center_count_; }
  std::uint64_t device_id() const { return device_id_; }
  FieldView view() const;

 private:
  DeviceBuffer memory_;
  int center_count_ = 0;
  std::uint64_t device_id_ = 0;
};

}  // namespace posekit::cuda
