// The Vulkan objects every posekit device owns: instance (with the validation layer when asked
// for), the chosen physical device, a logical device with shaderFloat64 enabled, one compute queue
// and its command pool. Buffers, pipelines and fields keep the context alive through a shared_ptr,
// so a field may outlive the Device it was uploaded to.
#pragma once

#include "vulkan_discovery.hpp"

#include <vulkan/vulkan.h>

#include <cstdint>
#include <memory>

namespace posekit::vulkan {

/// How the host touches a buffer: `upload` (host writes, device reads: device-local memory
/// preferred) or `readback` (device writes, host reads: host-cached memory preferred). Both are
/// host-visible and host-coherent, so the host maps them directly.
enum class MemoryUse { upload, readback };

class Context {
 public:
  /// Creates every object; with `validation`, VK_LAYER_KHRONOS_validation (with synchronization
  /// validation where the layer offers it) and a messenger feeding vulkan_validation.hpp's log.
  /// Throws DeviceError when no suitable device exists or the layer is missing.
  explicit Context(bool validation);
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  VkDevice device() const { return device_; }
  VkPhysicalDevice physical_device() const { return physical_device_; }
  VkQueue queue() const { return queue_; }
  std::uint32_t queue_family() const { return queue_family_; }
  const DiscoveredDevice& description() const { return description_; }
  const VkPhysicalDeviceLimits& limits() const { return limits_; }
  bool validation() const { return validation_; }
  /// The pool of every CommandSlot; like the queue, used by one thread at a time (the Device's
  /// lock).
  VkCommandPool command_pool() const { return command_pool_; }

  /// A memory type among `allowed` (VkMemoryRequirements::memoryTypeBits) for `use`; throws
  /// DeviceError when none is host-visible and host-coherent.
  std::uint32_t memory_type(std::uint32_t allowed, MemoryUse use) const;

 private:
  void destroy() noexcept;

  bool validation_ = false;
  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkPhysicalDevice physical_device_ = VK_NULL_HANDLE;
  DiscoveredDevice description_;
  VkPhysicalDeviceLimits limits_{};
  VkPhysicalDeviceMemoryProperties memory_{};
  std::uint32_t queue_family_ = 0;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  VkCommandPool command_pool_ = VK_NULL_HANDLE;
};

/// True once the process has begun to exit after a Context was created. Vulkan objects that are
/// still alive then (devices held in static variables) are left to the operating system: the
/// driver and the layers, loaded after those variables were made, have torn down their own state
/// first, so calling into them would crash.
bool process_exiting();

/// One command buffer with its fence: record, submit, wait; reused call after call.
class CommandSlot {
 public:
  explicit CommandSlot(std::shared_ptr<const Context> context);
  ~CommandSlot();
  CommandSlot(const CommandSlot&) = delete;
  CommandSlot& operator=(const CommandSlot&) = delete;

  /// Waits for the previous submission if one is pending, then starts recording.
  VkCommandBuffer begin();
  /// Ends recording and submits to the context's queue.
  void submit();
  /// Waits until the last submission has finished; does nothing when none is pending.
  void wait();
  bool pending() const { return pending_; }
  /// wait() that never throws, for cleanup paths.
  void wait_quietly() noexcept;

 private:
  std::shared_ptr<const Context> context_;
  VkCommandBuffer buffer_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
  bool pending_ = false;
};

/// Makes every shader write of the recorded work visible to host reads after the fence.
void record_shader_to_host_barrier(VkCommandBuffer commands);

/// Makes the shader writes of one dispatch visible to the shader reads and writes of the next.
void record_shader_to_shader_barrier(VkCommandBuffer commands);

}  // namespace posekit::vulkan
