#include "vulkan_buffer.hpp"

#include "vulkan_check.hpp"

#include <algorithm>
#include <utility>

namespace posekit::vulkan {

Buffer::Buffer(std::shared_ptr<const Context> context, VkDeviceSize bytes, VkBufferUsageFlags usage,
               MemoryUse use)
    : context_(std::move(context)), size_(bytes) {
  const VkDevice device = context_->device();
  try {
    VkBufferCreateInfo buffer_info{};
    buffer_info.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
    buffer_info.size = bytes;
    buffer_info.usage = usage;
    buffer_info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    POSEKIT_VK_CHECK(vkCreateBuffer(device, &buffer_info, nullptr, &buffer_));
    VkMemoryRequirements requirements{};
    vkGetBufferMemoryRequirements(device, buffer_, &requirements);
    VkMemoryAllocateInfo allocate{};
    allocate.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
    allocate.allocationSize = requirements.size;
    allocate.memoryTypeIndex = context_->memory_type(requirements.memoryTypeBits, use);
    POSEKIT_VK_CHECK(vkAllocateMemory(device, &allocate, nullptr, &memory_));
    POSEKIT_VK_CHECK(vkBindBufferMemory(device, buffer_, memory_, 0));
    POSEKIT_VK_CHECK(vkMapMemory(device, memory_, 0, VK_WHOLE_SIZE, 0, &mapped_));
  } catch (...) {
    release();
    throw;
  }
}

Buffer::~Buffer() { release(); }

Buffer::Buffer(Buffer&& other) noexcept
    : context_(std::move(other.context_)),
      buffer_(std::exchange(other.buffer_, VK_NULL_HANDLE)),
      memory_(std::exchange(other.memory_, VK_NULL_HANDLE)),
      mapped_(std::exchange(other.mapped_, nullptr)),
      size_(std::exchange(other.size_, 0)) {}

Buffer& Buffer::operator=(Buffer&& other) noexcept {
  if (this != &other) {
    release();
    context_ = std::move(other.context_);
    buffer_ = std::exchange(other.buffer_, VK_NULL_HANDLE);
    memory_ = std::exchange(other.memory_, VK_NULL_HANDLE);
    mapped_ = std::exchange(other.mapped_, nullptr);
    size_ = std::exchange(other.size_, 0);
  }
  return *this;
}

void Buffer::release() noexcept {
  if (!context_) return;
  if (process_exiting()) {
    context_.reset();
    return;
  }
  const VkDevice device = context_->device();
  if (buffer_ != VK_NULL_HANDLE) vkDestroyBuffer(device, buffer_, nullptr);
  // Freeing the memory unmaps it.
  if (memory_ != VK_NULL_HANDLE) vkFreeMemory(device, memory_, nullptr);
  buffer_ = VK_NULL_HANDLE;
  memory_ = VK_NULL_HANDLE;
  mapped_ = nullptr;
  size_ = 0;
  context_.reset();
}

Buffer& ScratchBuffer::at_least(VkDeviceSize bytes) {
  bytes = std::max<VkDeviceSize>(bytes, 256);
  if (buffer_.size() < bytes) {
    buffer_ = Buffer();  // free the old memory before allocating the new
    // A little headroom, so that slowly growing calls do not reallocate every time.
    buffer_ = Buffer(context_, bytes + bytes / 4, usage_, use_);
  }
  return buffer_;
}

}  // namespace posekit::vulkan
