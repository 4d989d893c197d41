// A field uploaded to a Vulkan device: centers and weights in the chunked layout of
// shaders/rbf_field.glsl, and the polynomial part.
#pragma once

#include "vulkan_buffer.hpp"
#include "vulkan_pipeline.hpp"

#include <posekit/device.hpp>

#include <cstdint>
#include <memory>

namespace posekit::vulkan {

class VulkanField final : public DeviceField {
 public:
  /// Copies `field` into device buffers; device_id names the device that owns it. Throws
  /// ArgumentError when the weights do not have one row per center or the centers do not fit one
  /// storage buffer of the device.
  VulkanField(std::shared_ptr<const Context> context, const RbfField& field,
              std::uint64_t device_id);

  int center_count() const override { return center_count_; }
  std::uint64_t device_id() const { return device_id_; }

  /// Points the field's bindings (FieldCenters, FieldPolynomial, FieldChunk[]) of descriptor set
  /// `set` of `pipeline` at this field's buffers.
  void bind_to(ComputePipeline& pipeline, std::uint32_t set) const;

 private:
  std::shared_ptr<const Context> context_;
  int center_count_;
  std::uint64_t device_id_;
  Buffer centers_;     // whole chunks of kChunkBytes, at least one
  Buffer polynomial_;  // 15 dvec4: the coefficients of one term per row
};

}  // namespace posekit::vulkan
