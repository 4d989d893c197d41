#include "vulkan_device.hpp"

#include "loop_budget.hpp"
#include "shader_interface.hpp"
#include "spirv_library.hpp"
#include "vulkan_validation.hpp"

#include <posekit/error.hpp>

#include <algorithm>
#include <string>

namespace posekit::vulkan {
namespace {

constexpr std::uint64_t kDefaultChunkCap = std::uint64_t{64} << 20;

constexpr VkBufferUsageFlags kStorage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;

std::shared_ptr<const Context> make_context(bool validation) {
  return std::make_shared<const Context>(validation);
}

// The bindings of a shader that reads a field (rbf_field.glsl) plus `own` ones.
std::vector<BindingLayout> field_bindings(std::vector<BindingLayout> own) {
  own.push_back({kCentersBinding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
  own.push_back({kPolynomialBinding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
  own.push_back({kChunksBinding, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, kUniformChunks});
  return own;
}

}  // namespace

DeviceInfo describe(const DiscoveredDevice& device) {
  DeviceInfo info;
  info.backend = "vulkan";
  info.name = device.device_name;
  info.driver = device.driver;
  info.fp64 = true;  // a device without shaderFloat64 is never chosen
  info.emulated_on_cpu = device.is_cpu;
  info.max_buffer_bytes = device.max_storage_buffer_bytes;
  info.compute_units = 0;  // Vulkan does not report one
  return info;
}

VulkanDevice::VulkanDevice(bool validation, DeviceTuning tuning)
    : Device(Calls::serialized),
      context_(make_context(validation)),
      chunk_bytes_(std::min<std::uint64_t>(
          context_->limits().maxStorageBufferRange,
          tuning.max_chunk_bytes > 0 ? tuning.max_chunk_bytes : kDefaultChunkCap)),
      loop_iterations_(tuning.loop_iterations > 0             ? tuning.loop_iterations
                       : context_->description().loop_limited ? kLavapipeLoopIterations
                                                              : kUnlimitedLoopIterations),
      assembly_points_(context_, kStorage, MemoryUse::upload),
      assembly_centers_{
          ScratchBuffer(context_, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, MemoryUse::upload),
          ScratchBuffer(context_, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, MemoryUse::upload)},
      assembly_blocks_{ScratchBuffer(context_, kStorage, MemoryUse::readback),
                       ScratchBuffer(context_, kStorage, MemoryUse::readback)},
      evaluation_points_(context_, kStorage, MemoryUse::upload),
      evaluation_values_(context_, kStorage, MemoryUse::readback),
      evaluation_diagnostics_(context_, kStorage, MemoryUse::readback),
      rk45_states_(context_, kStorage, MemoryUse::readback) {
  // At least the 4 points of one assembly invocation (32 bytes each) per dispatch.
  if (chunk_bytes_ < 128) {
    throw ArgumentError("VulkanDevice: tuning.max_chunk_bytes must be at least 128, got " +
                        std::to_string(chunk_bytes_));
  }
  if (centers_per_evaluation(loop_iterations_) == 0) {
    throw ArgumentError("VulkanDevice: tuning.loop_iterations " + std::to_string(loop_iterations_) +
                        " leaves no room for a sum over centers");
  }
  const std::size_t first_message = validation_message_count();
  assemble_ = std::make_unique<ComputePipeline>(
      context_, spirv(Shader::rbf_assemble),
      std::vector<BindingLayout>{{kAssemblyPointsBinding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                                 {kAssemblyCentersBinding, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},
                                 {kAssemblyBlockBinding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}},
      static_cast<std::uint32_t>(sizeof(AssemblyPush)), 2);
  evaluate_ = std::make_unique<ComputePipeline>(
      context_, spirv(Shader::rbf_evaluate),
      field_bindings({{kInputBinding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                      {kOutputBinding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                      {kDiagnosticsBinding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}}),
      static_cast<std::uint32_t>(sizeof(EvaluationPush)));
  rk45_ = std::make_unique<ComputePipeline>(
      context_, spirv(Shader::rk45_integrate),
      field_bindings({{kInputBinding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}}),
      static_cast<std::uint32_t>(sizeof(Rk45Push)));
  for (auto& slot : slots_) slot = std::make_unique<CommandSlot>(context_);
  if (context_->validation()) throw_if_validation_messages(first_message, "Vulkan device creation");
}

VulkanDevice::~VulkanDevice() {
  if (process_exiting()) return;
  for (auto& slot : slots_) {
    if (slot) slot->wait_quietly();
  }
}

DeviceInfo VulkanDevice::info() const { return describe(context_->description()); }

std::unique_ptr<DeviceField> VulkanDevice::do_upload_field(const RbfField& field) {
  return std::make_unique<VulkanField>(context_, field, id());
}

void VulkanDevice::run(const char* operation, const std::function<void()>& body) {
  const std::size_t first_message = validation_message_count();
  try {
    body();
  } catch (...) {
    // Nothing may still run on buffers that the next call reallocates.
    for (auto& slot : slots_) slot->wait_quietly();
    throw;
  }
  if (context_->validation()) throw_if_validation_messages(first_message, operation);
}

Eigen::Index VulkanDevice::batch_size(std::uint64_t bytes_per_point) const {
  const std::uint64_t by_buffer = chunk_bytes_ / bytes_per_point;
  const std::uint64_t by_dispatch =
      std::uint64_t{context_->limits().maxComputeWorkGroupCount[0]} * kWorkGroupSize;
  return static_cast<Eigen::Index>(std::max<std::uint64_t>(1, std::min(by_buffer, by_dispatch)));
}

}  // namespace posekit::vulkan
