#include "vulkan_context.hpp"

#include "vulkan_check.hpp"
#include "vulkan_validation.hpp"

#include <posekit/error.hpp>

#include <atomic>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

namespace posekit::vulkan {
namespace {

bool layer_has_extension(const char* layer, const char* extension) {
  std::uint32_t count = 0;
  if (vkEnumerateInstanceExtensionProperties(layer, &count, nullptr) != VK_SUCCESS) return false;
  std::vector<VkExtensionProperties> extensions(count);
  if (vkEnumerateInstanceExtensionProperties(layer, &count, extensions.data()) < 0) return false;
  extensions.resize(count);
  for (const VkExtensionProperties& properties : extensions) {
    if (std::strcmp(properties.extensionName, extension) == 0) return true;
  }
  return false;
}

std::atomic<bool>& exit_flag() {
  static std::atomic<bool> flag{false};
  return flag;
}

void note_exit() { exit_flag() = true; }

}  // namespace

bool process_exiting() { return exit_flag(); }

Context::Context(bool validation) : validation_(validation) {
  const std::size_t first_message = validation_message_count();
  try {
    VkApplicationInfo application{};
    application.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
    application.pApplicationName = "posekit";
    application.pEngineName = "posekit";
    application.apiVersion = VK_API_VERSION_1_2;

    std::vector<const char*> layers;
    std::vector<const char*> extensions;
    // Chained into the instance's create info, the messenger also hears about vkCreateInstance
    // and vkDestroyInstance.
    VkDebugUtilsMessengerCreateInfoEXT messenger_info = validation_messenger_info();
    VkValidationFeaturesEXT features{};
    const VkValidationFeatureEnableEXT enabled_features[] = {
        VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
    const void* chain = nullptr;
    if (validation_) {
      if (!validation_layer_installed()) throw DeviceError(missing_validation_layer_reason());
      if (!layer_has_extension(kValidationLayerName, VK_EXT_DEBUG_UTILS_EXTENSION_NAME) &&
          !layer_has_extension(nullptr, VK_EXT_DEBUG_UTILS_EXTENSION_NAME)) {
        throw DeviceError(std::string("Vulkan validation needs ") +
                          VK_EXT_DEBUG_UTILS_EXTENSION_NAME +
                          ", which neither the loader nor the validation layer offers");
      }
      layers.push_back(kValidationLayerName);
      extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
      chain = &messenger_info;
      if (layer_has_extension(kValidationLayerName, VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME)) {
        extensions.push_back(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
        features.sType = VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT;
        features.enabledValidationFeatureCount = 1;
        features.pEnabledValidationFeatures = enabled_features;
        features.pNext = &messenger_info;
        chain = &features;
      }
    }
    VkInstanceCreateInfo instance_info{};
    instance_info.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
    instance_info.pNext = chain;
    instance_info.pApplicationInfo = &application;
    instance_info.enabledLayerCount = static_cast<std::uint32_t>(layers.size());
    instance_info.ppEnabledLayerNames = layers.data();
    instance_info.enabledExtensionCount = static_cast<std::uint32_t>(extensions.size());
    instance_info.ppEnabledExtensionNames = extensions.data();
    POSEKIT_VK_CHECK(vkCreateInstance(&instance_info, nullptr, &instance_));
    // Registered after the loader brought in the driver and layers (whose exit-time destructors
    // are registered by then): runs before those at exit.
    std::atexit(note_exit);

    if (validation_) {
      const auto create_messenger = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
          vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
      if (create_messenger == nullptr) {
        throw DeviceError("Vulkan validation: vkCreateDebugUtilsMessengerEXT is not available");
      }
      POSEKIT_VK_CHECK(create_messenger(instance_, &messenger_info, nullptr, &messenger_));
    }

    std::string reason;
    const std::optional<PhysicalDeviceChoice> choice = choose_physical_device(instance_, reason);
    if (!choice) throw DeviceError(reason);
    physical_device_ = choice->handle;
    description_ = choice->description;
    queue_family_ = choice->compute_queue_family;
    VkPhysicalDeviceProperties properties{};
    vkGetPhysicalDeviceProperties(physical_device_, &properties);
    limits_ = properties.limits;
    vkGetPhysicalDeviceMemoryProperties(physical_device_, &memory_);

    // choose_physical_device checked these features; they are enabled here explicitly, since a
    // shader may only use what the device was created with.
    VkPhysicalDeviceFeatures supported{};
    vkGetPhysicalDeviceFeatures(physical_device_, &supported);
    if (supported.shaderFloat64 != VK_TRUE) {
      throw DeviceError(description_.device_name +
                        " lacks shaderFloat64 (double precision in shaders)");
    }
    VkPhysicalDeviceFeatures enabled{};
    enabled.shaderFloat64 = VK_TRUE;
    enabled.shaderUniformBufferArrayDynamicIndexing = VK_TRUE;

    const float priority = 1.0F;
    VkDeviceQueueCreateInfo queue_info{};
    queue_info.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO;
    queue_info.queueFamilyIndex = queue_family_;
    queue_info.queueCount = 1;
    queue_info.pQueuePriorities = &priority;
    VkDeviceCreateInfo device_info{};
    device_info.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO;
    device_info.queueCreateInfoCount = 1;
    device_info.pQueueCreateInfos = &queue_info;
    device_info.pEnabledFeatures = &enabled;
    POSEKIT_VK_CHECK(vkCreateDevice(physical_device_, &device_info, nullptr, &device_));
    vkGetDeviceQueue(device_, queue_family_, 0, &queue_);

    VkCommandPoolCreateInfo pool_info{};
    pool_info.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
    pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pool_info.queueFamilyIndex = queue_family_;
    POSEKIT_VK_CHECK(vkCreateCommandPool(device_, &pool_info, nullptr, &command_pool_));
    if (validation_)
      throw_if_validation_messages(first_message, "Vulkan instance and device creation");
  } catch (...) {
    destroy();
    throw;
  }
}

Context::~Context() { destroy(); }

void Context::destroy() noexcept {
  if (process_exiting()) return;
  if (device_ != VK_NULL_HANDLE) {
    vkDeviceWaitIdle(device_);
    if (command_pool_ != VK_NULL_HANDLE) vkDestroyCommandPool(device_, command_pool_, nullptr);
    command_pool_ = VK_NULL_HANDLE;
    vkDestroyDevice(device_, nullptr);
    device_ = VK_NULL_HANDLE;
  }
  if (messenger_ != VK_NULL_HANDLE) {
    const auto destroy_messenger = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
    if (destroy_messenger != nullptr) destroy_messenger(instance_, messenger_, nullptr);
    messenger_ = VK_NULL_HANDLE;
  }
  if (instance_ != VK_NULL_HANDLE) {
    vkDestroyInstance(instance_, nullptr);
    instance_ = VK_NULL_HANDLE;
  }
}

std::uint32_t Context::memory_type(std::uint32_t allowed, MemoryUse use) const {
  const VkMemoryPropertyFlags required =
      VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  const VkMemoryPropertyFlags preferred = use == MemoryUse::upload
                                              ? VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT
                                              : VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
  std::uint32_t found = std::numeric_limits<std::uint32_t>::max();
  for (std::uint32_t i = 0; i < memory_.memoryTypeCount; ++i) {
    if ((allowed & (1U << i)) == 0) continue;
    const VkMemoryPropertyFlags flags = memory_.memoryTypes[i].propertyFlags;
    if ((flags & required) != required) continue;
    if ((flags & preferred) == preferred) return i;
    if (found == std::numeric_limits<std::uint32_t>::max()) found = i;
  }
  if (found == std::numeric_limits<std::uint32_t>::max()) {
    throw DeviceError(description_.device_name +
                      " has no host-visible, host-coherent memory for a buffer");
  }
  return found;
}

CommandSlot::CommandSlot(std::shared_ptr<const Context> context) : context_(std::move(context)) {
  VkCommandBufferAllocateInfo allocate{};
  allocate.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
  allocate.commandPool = context_->command_pool();
  allocate.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  allocate.commandBufferCount = 1;
  POSEKIT_VK_CHECK(vkAllocateCommandBuffers(context_->device(), &allocate, &buffer_));
  VkFenceCreateInfo fence_info{};
  fence_info.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
  const VkResult created = vkCreateFence(context_->device(), &fence_info, nullptr, &fence_);
  if (created != VK_SUCCESS) {
    vkFreeCommandBuffers(context_->device(), context_->command_pool(), 1, &buffer_);
    check(created, "vkCreateFence", __FILE__, __LINE__);
  }
}

CommandSlot::~CommandSlot() {
  if (process_exiting()) return;
  wait_quietly();
  vkFreeCommandBuffers(context_->device(), context_->command_pool(), 1, &buffer_);
  vkDestroyFence(context_->device(), fence_, nullptr);
}

VkCommandBuffer CommandSlot::begin() {
  wait();
  POSEKIT_VK_CHECK(vkResetCommandBuffer(buffer_, 0));
  VkCommandBufferBeginInfo begin_info{};
  begin_info.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
  begin_info.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  POSEKIT_VK_CHECK(vkBeginCommandBuffer(buffer_, &begin_info));
  return buffer_;
}

void CommandSlot::submit() {
  POSEKIT_VK_CHECK(vkEndCommandBuffer(buffer_));
  VkSubmitInfo submit_info{};
  submit_info.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
  submit_info.commandBufferCount = 1;
  submit_info.pCommandBuffers = &buffer_;
  POSEKIT_VK_CHECK(vkQueueSubmit(context_->queue(), 1, &submit_info, fence_));
  pending_ = true;
}

void CommandSlot::wait() {
  if (!pending_) return;
  // Cleared first: after a failed wait (a lost device) the slot is not waited on forever.
  pending_ = false;
  POSEKIT_VK_CHECK(vkWaitForFences(context_->device(), 1, &fence_, VK_TRUE,
                                   std::numeric_limits<std::uint64_t>::max()));
  POSEKIT_VK_CHECK(vkResetFences(context_->device(), 1, &fence_));
}

void CommandSlot::wait_quietly() noexcept {
  if (!pending_) return;
  pending_ = false;
  vkWaitForFences(context_->device(), 1, &fence_, VK_TRUE,
                  std::numeric_limits<std::uint64_t>::max());
  vkResetFences(context_->device(), 1, &fence_);
}

void record_shader_to_host_barrier(VkCommandBuffer commands) {
  VkMemoryBarrier barrier{};
  barrier.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
  barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
  barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT,
                       0, 1, &barrier, 0, nullptr, 0, nullptr);
}

void record_shader_to_shader_barrier(VkCommandBuffer commands) {
  VkMemoryBarrier barrier{};
  barrier.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
  barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
  barrier.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
  vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                       VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1, &barrier, 0, nullptr, 0,
                       nullptr);
}

}  // namespace posekit::vulkan
