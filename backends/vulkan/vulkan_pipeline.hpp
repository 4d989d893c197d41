// A compute pipeline built once from embedded SPIR-V: its descriptor-set layout, a pipeline layout
// with one push-constant range, and a small pool of descriptor sets that the operations rewrite
// before each use.
#pragma once

#include "vulkan_context.hpp"

#include <vulkan/vulkan.h>

#include <cstdint>
#include <memory>
#include <vector>

namespace posekit::vulkan {

/// One binding of set 0: `count` descriptors of `type` (an array when count > 1).
struct BindingLayout {
  std::uint32_t binding;
  VkDescriptorType type;
  std::uint32_t count = 1;
};

/// A buffer range for one descriptor.
struct BufferRange {
  VkBuffer buffer;
  VkDeviceSize offset;
  VkDeviceSize bytes;
};

class ComputePipeline {
 public:
  /// Builds the pipeline from `spirv` (entry point "main"); `sets` descriptor sets are allocated
  /// so that that many submissions can be in flight at once. Throws DeviceError.
  ComputePipeline(std::shared_ptr<const Context> context, const std::vector<std::uint32_t>& spirv,
                  std::vector<BindingLayout> bindings, std::uint32_t push_constant_bytes,
                  std::uint32_t sets = 1);
  ~ComputePipeline();
  ComputePipeline(const ComputePipeline&) = delete;
  ComputePipeline& operator=(const ComputePipeline&) = delete;

  /// Points `binding` of descriptor set `set` at `ranges` (one per array element). Only while no
  /// pending submission uses that set.
  void write(std::uint32_t set, std::uint32_t binding, const std::vector<BufferRange>& ranges);

  /// Binds the pipeline and descriptor set `set`, and pushes `push_constant_bytes` from
  /// `constants`.
  void bind(VkCommandBuffer commands, std::uint32_t set, const void* constants) const;
  /// Pushes new constants for the following dispatches of the bound pipeline.
  void push(VkCommandBuffer commands, const void* constants) const;

 private:
  void destroy() noexcept;

  std::shared_ptr<const Context> context_;
  std::vector<BindingLayout> bindings_;
  std::uint32_t push_constant_bytes_;
  VkDescriptorSetLayout set_layout_ = VK_NULL_HANDLE;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  std::vector<VkDescriptorSet> sets_;
};

}  // namespace posekit::vulkan
