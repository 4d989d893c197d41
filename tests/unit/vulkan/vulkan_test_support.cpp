#include "vulkan_test_support.hpp"

#include "vulkan/vulkan_buffer.hpp"
#include "vulkan/vulkan_discovery.hpp"
#include "vulkan/vulkan_pipeline.hpp"

#include "kernel_math_probe.spv.h"

#include <cstring>
#include <iterator>

namespace posekit::vulkan::testing {

std::unique_ptr<VulkanDevice> make_validated_device(std::string& reason, DeviceTuning tuning) {
  const Discovery discovery = discover_device();
  if (!discovery.device) {
    reason = "no usable Vulkan device here: " + discovery.reason;
    return nullptr;
  }
  return std::make_unique<VulkanDevice>(true, tuning);
}

std::vector<double> run_probe(const VulkanDevice& device, Probe probe,
                              const std::vector<double>& inputs) {
  if (inputs.empty()) return {};
  const std::shared_ptr<const Context>& context = device.context();
  const std::vector<std::uint32_t> code(std::begin(posekit_spirv_kernel_math_probe),
                                        std::end(posekit_spirv_kernel_math_probe));
  struct Push {
    std::uint32_t mode;
    std::uint32_t count;
  };
  ComputePipeline pipeline(
      context, code,
      {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}, {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}},
      sizeof(Push));
  const VkDeviceSize bytes = inputs.size() * sizeof(double);
  Buffer input(context, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::upload);
  Buffer output(context, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::readback);
  std::memcpy(input.data(), inputs.data(), bytes);
  pipeline.write(0, 0, {{input.handle(), 0, bytes}});
  pipeline.write(0, 1, {{output.handle(), 0, bytes}});
  const Push push{static_cast<std::uint32_t>(probe), static_cast<std::uint32_t>(inputs.size())};
  CommandSlot slot(context);
  const VkCommandBuffer commands = slot.begin();
  pipeline.bind(commands, 0, &push);
  vkCmdDispatch(commands, static_cast<std::uint32_t>((inputs.size() + 63) / 64), 1, 1);
  record_shader_to_host_barrier(commands);
  slot.submit();
  slot.wait();
  std::vector<double> outputs(inputs.size());
  std::memcpy(outputs.data(), output.data(), bytes);
  return outputs;
}

}  // namespace posekit::vulkan::testing
