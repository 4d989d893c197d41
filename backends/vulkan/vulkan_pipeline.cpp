#include "vulkan_pipeline.hpp"

#include "vulkan_check.hpp"

#include <posekit/error.hpp>

#include <map>
#include <string>

namespace posekit::vulkan {

ComputePipeline::ComputePipeline(std::shared_ptr<const Context> context,
                                 const std::vector<std::uint32_t>& spirv,
                                 std::vector<BindingLayout> bindings,
                                 std::uint32_t push_constant_bytes, std::uint32_t sets)
    : context_(std::move(context)),
      bindings_(std::move(bindings)),
      push_constant_bytes_(push_constant_bytes) {
  const VkDevice device = context_->device();
  VkShaderModule module = VK_NULL_HANDLE;
  try {
    std::vector<VkDescriptorSetLayoutBinding> layout_bindings;
    std::map<VkDescriptorType, std::uint32_t> descriptors_per_set;
    for (const BindingLayout& binding : bindings_) {
      VkDescriptorSetLayoutBinding layout_binding{};
      layout_binding.binding = binding.binding;
      layout_binding.descriptorType = binding.type;
      layout_binding.descriptorCount = binding.count;
      layout_binding.stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
      layout_bindings.push_back(layout_binding);
      descriptors_per_set[binding.type] += binding.count;
    }
    VkDescriptorSetLayoutCreateInfo set_layout_info{};
    set_layout_info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
    set_layout_info.bindingCount = static_cast<std::uint32_t>(layout_bindings.size());
    set_layout_info.pBindings = layout_bindings.data();
    POSEKIT_VK_CHECK(vkCreateDescriptorSetLayout(device, &set_layout_info, nullptr, &set_layout_));

    VkPushConstantRange push_range{};
    push_range.stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
    push_range.offset = 0;
    push_range.size = push_constant_bytes_;
    VkPipelineLayoutCreateInfo layout_info{};
    layout_info.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
    layout_info.setLayoutCount = 1;
    layout_info.pSetLayouts = &set_layout_;
    layout_info.pushConstantRangeCount = push_constant_bytes_ > 0 ? 1 : 0;
    layout_info.pPushConstantRanges = &push_range;
    POSEKIT_VK_CHECK(vkCreatePipelineLayout(device, &layout_info, nullptr, &layout_));

    VkShaderModuleCreateInfo module_info{};
    module_info.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
    module_info.codeSize = spirv.size() * sizeof(std::uint32_t);
    module_info.pCode = spirv.data();
    POSEKIT_VK_CHECK(vkCreateShaderModule(device, &module_info, nullptr, &module));
    VkComputePipelineCreateInfo pipeline_info{};
    pipeline_info.sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO;
    pipeline_info.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    pipeline_info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    pipeline_info.stage.module = module;
    pipeline_info.stage.pName = "main";
    pipeline_info.layout = layout_;
    POSEKIT_VK_CHECK(
        vkCreateComputePipelines(device, VK_NULL_HANDLE, 1, &pipeline_info, nullptr, &pipeline_));
    vkDestroyShaderModule(device, module, nullptr);
    module = VK_NULL_HANDLE;

    std::vector<VkDescriptorPoolSize> pool_sizes;
    for (const auto& [type, count] : descriptors_per_set)
      pool_sizes.push_back({type, count * sets});
    VkDescriptorPoolCreateInfo pool_info{};
    pool_info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
    pool_info.maxSets = sets;
    pool_info.poolSizeCount = static_cast<std::uint32_t>(pool_sizes.size());
    pool_info.pPoolSizes = pool_sizes.data();
    POSEKIT_VK_CHECK(vkCreateDescriptorPool(device, &pool_info, nullptr, &pool_));
    const std::vector<VkDescriptorSetLayout> layouts(sets, set_layout_);
    sets_.resize(sets);
    VkDescriptorSetAllocateInfo allocate{};
    allocate.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
    allocate.descriptorPool = pool_;
    allocate.descriptorSetCount = sets;
    allocate.pSetLayouts = layouts.data();
    POSEKIT_VK_CHECK(vkAllocateDescriptorSets(device, &allocate, sets_.data()));
  } catch (...) {
    if (module != VK_NULL_HANDLE) vkDestroyShaderModule(device, module, nullptr);
    destroy();
    throw;
  }
}

ComputePipeline::~ComputePipeline() { destroy(); }

void ComputePipeline::destroy() noexcept {
  if (process_exiting()) return;
  const VkDevice device = context_->device();
  // Destroying the pool frees its sets.
  if (pool_ != VK_NULL_HANDLE) vkDestroyDescriptorPool(device, pool_, nullptr);
  if (pipeline_ != VK_NULL_HANDLE) vkDestroyPipeline(device, pipeline_, nullptr);
  if (layout_ != VK_NULL_HANDLE) vkDestroyPipelineLayout(device, layout_, nullptr);
  if (set_layout_ != VK_NULL_HANDLE) vkDestroyDescriptorSetLayout(device, set_layout_, nullptr);
  pool_ = VK_NULL_HANDLE;
  pipeline_ = VK_NULL_HANDLE;
  layout_ = VK_NULL_HANDLE;
  set_layout_ = VK_NULL_HANDLE;
  sets_.clear();
}

void ComputePipeline::write(std::uint32_t set, std::uint32_t binding,
                            const std::vector<BufferRange>& ranges) {
  const BindingLayout* layout = nullptr;
  for (const BindingLayout& candidate : bindings_) {
    if (candidate.binding == binding) layout = &candidate;
  }
  if (layout == nullptr || set >= sets_.size() || ranges.size() != layout->count) {
    throw DeviceError("ComputePipeline::write: set " + std::to_string(set) + ", binding " +
                      std::to_string(binding) + " with " + std::to_string(ranges.size()) +
                      " ranges does not match the pipeline's layout");
  }
  std::vector<VkDescriptorBufferInfo> infos;
  infos.reserve(ranges.size());
  for (const BufferRange& range : ranges)
    infos.push_back({range.buffer, range.offset, range.bytes});
  VkWriteDescriptorSet write{};
  write.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
  write.dstSet = sets_[set];
  write.dstBinding = binding;
  write.descriptorCount = static_cast<std::uint32_t>(infos.size());
  write.descriptorType = layout->type;
  write.pBufferInfo = infos.data();
  vkUpdateDescriptorSets(context_->device(), 1, &write, 0, nullptr);
}

void ComputePipeline::bind(VkCommandBuffer commands, std::uint32_t set,
                           const void* constants) const {
  vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
  vkCmdBindDescriptorSets(commands, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, 1, &sets_.at(set),
                          0, nullptr);
  push(commands, constants);
}

void ComputePipeline::push(VkCommandBuffer commands, const void* constants) const {
  if (push_constant_bytes_ > 0) {
    vkCmdPushConstants(commands, layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, push_constant_bytes_,
                       constants);
  }
}

}  // namespace posekit::vulkan
