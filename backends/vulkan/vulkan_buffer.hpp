// A Vulkan buffer with its own memory, mapped for the host for its whole life.
#pragma once

#include "vulkan_context.hpp"

#include <vulkan/vulkan.h>

#include <cstddef>
#include <memory>

namespace posekit::vulkan {

class Buffer {
 public:
  Buffer() = default;
  /// A buffer of `bytes` (> 0) for `usage` in memory chosen for `use`; throws DeviceError.
  Buffer(std::shared_ptr<const Context> context, VkDeviceSize bytes, VkBufferUsageFlags usage,
         MemoryUse use);
  ~Buffer();
  Buffer(Buffer&& other) noexcept;
  Buffer& operator=(Buffer&& other) noexcept;
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;

  VkBuffer handle() const { return buffer_; }
  VkDeviceSize size() const { return size_; }
  /// The host's view of the whole buffer (coherent: no flush or invalidate needed).
  void* data() const { return mapped_; }
  template <typename T>
  T* as() const {
    return static_cast<T*>(mapped_);
  }

 private:
  void release() noexcept;

  std::shared_ptr<const Context> context_;
  VkBuffer buffer_ = VK_NULL_HANDLE;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  void* mapped_ = nullptr;
  VkDeviceSize size_ = 0;
};

/// A buffer that is reused from call to call and reallocated only when a call needs more.
class ScratchBuffer {
 public:
  ScratchBuffer(std::shared_ptr<const Context> context, VkBufferUsageFlags usage, MemoryUse use)
      : context_(std::move(context)), usage_(usage), use_(use) {}

  /// The buffer, at least `bytes` large. Only call when no submitted work still uses it.
  Buffer& at_least(VkDeviceSize bytes);
  /// The buffer as the last at_least() left it.
  Buffer& current() { return buffer_; }

 private:
  std::shared_ptr<const Context> context_;
  VkBufferUsageFlags usage_;
  MemoryUse use_;
  Buffer buffer_;
};

}  // namespace posekit::vulkan
