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
  /// Copies `field` (checked by Device::upload_field) into device buffers for the device
  /// numbered device_id. Throws ArgumentError when the centers do not fit one storage buffer.
  VulkanField(std::shared_ptr<const Context> context, const RbfField& field,
              std::uint64_t device_id);

  /// Points the field's bindings (FieldCenters, FieldPolynomial, FieldChunk[]) of descriptor set
  /// `set` of `pipeline` at this field's buffers.
  void bind_to(ComputePipeline& pipeline, std::uint32_t set) const;

 private:
  std::shared_ptr<const Context> context_;
  Buffer centers_;     // whole chunks of kChunkBytes, at least one
  Buffer polynomial_;  // 15 dvec4: the coefficients of one term per row
};

}  // namespace posekit::vulkan
