#include "vulkan_discovery.hpp"

#include "vulkan_check.hpp"

#include <cstdlib>
#include <exception>
#include <vector>

namespace posekit::vulkan {
namespace {

// Destroys the probe's instance on every path out of discover_device().
class ScopedInstance {
 public:
  explicit ScopedInstance(VkInstance instance) : instance_(instance) {}
  ~ScopedInstance() {
    if (instance_ != VK_NULL_HANDLE) vkDestroyInstance(instance_, nullptr);
  }
  ScopedInstance(const ScopedInstance&) = delete;
  ScopedInstance& operator=(const ScopedInstance&) = delete;

 private:
  VkInstance instance_;
};

// Lower is better: discrete, integrated, virtual, other, CPU.
int preference(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
      return 0;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
      return 1;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
      return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
      return 4;
    default:
      return 3;
  }
}

std::optional<std::uint32_t> compute_queue_family(VkPhysicalDevice device) {
  std::uint32_t count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, nullptr);
  std::vector<VkQueueFamilyProperties> families(count);
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families.data());
  for (std::uint32_t i = 0; i < count; ++i) {
    if ((families[i].queueFlags & VK_QUEUE_COMPUTE_BIT) != 0 && families[i].queueCount > 0)
      return i;
  }
  return std::nullopt;
}

// What the device lacks for posekit's shaders, or "" when it has everything.
std::string missing_requirement(VkPhysicalDevice device,
                                const VkPhysicalDeviceProperties& properties) {
  if (properties.apiVersion < VK_API_VERSION_1_2)
    return "Vulkan 1.2 (the driver offers an older version)";
  VkPhysicalDeviceFeatures features{};
  vkGetPhysicalDeviceFeatures(device, &features);
  if (features.shaderFloat64 != VK_TRUE) return "shaderFloat64 (double precision in shaders)";
  if (features.shaderUniformBufferArrayDynamicIndexing != VK_TRUE) {
    return "shaderUniformBufferArrayDynamicIndexing";
  }
  if (!compute_queue_family(device)) return "a compute queue";
  VkPhysicalDeviceSubgroupProperties subgroup{};
  subgroup.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES;
  VkPhysicalDeviceProperties2 with_subgroup{};
  with_subgroup.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2;
  with_subgroup.pNext = &subgroup;
  vkGetPhysicalDeviceProperties2(device, &with_subgroup);
  if ((subgroup.supportedStages & VK_SHADER_STAGE_COMPUTE_BIT) == 0 ||
      (subgroup.supportedOperations & VK_SUBGROUP_FEATURE_VOTE_BIT) == 0) {
    return "subgroup vote operations in compute shaders";
  }
  const VkPhysicalDeviceLimits& limits = properties.limits;
  if (limits.maxUniformBufferRange < 65536) return "64 KiB uniform buffers (maxUniformBufferRange)";
  if (limits.maxPerStageDescriptorUniformBuffers < 12 ||
      limits.maxPerStageDescriptorStorageBuffers < 4) {
    return "12 uniform and 4 storage buffers per shader stage";
  }
  if (limits.maxComputeWorkGroupInvocations < 64 || limits.maxComputeWorkGroupSize[0] < 64) {
    return "work groups of 64 invocations";
  }
  return "";
}

}  // namespace

std::optional<PhysicalDeviceChoice> choose_physical_device(VkInstance instance,
                                                           std::string& reason) {
  std::uint32_t count = 0;
  if (vkEnumeratePhysicalDevices(instance, &count, nullptr) != VK_SUCCESS) count = 0;
  std::vector<VkPhysicalDevice> devices(count);
  if (count > 0 && vkEnumeratePhysicalDevices(instance, &count, devices.data()) < 0) count = 0;
  devices.resize(count);
  if (devices.empty()) {
    reason = "no Vulkan physical device found";
    return std::nullopt;
  }

  const char* wanted = std::getenv("POSEKIT_VULKAN_DEVICE");
  std::optional<PhysicalDeviceChoice> best;
  int best_preference = 0;
  std::string rejected;
  for (VkPhysicalDevice device : devices) {
    VkPhysicalDeviceDriverProperties driver{};
    driver.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES;
    VkPhysicalDeviceProperties2 properties{};
    properties.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2;
    // VkPhysicalDeviceDriverProperties is Vulkan 1.2: chained only where the device has 1.2 (an
    // older one is rejected below anyway).
    VkPhysicalDeviceProperties basic{};
    vkGetPhysicalDeviceProperties(device, &basic);
    if (basic.apiVersion >= VK_API_VERSION_1_2) properties.pNext = &driver;
    vkGetPhysicalDeviceProperties2(device, &properties);
    const std::string name = properties.properties.deviceName;
    if (wanted != nullptr && name.find(wanted) == std::string::npos) continue;
    const std::string missing = missing_requirement(device, properties.properties);
    if (!missing.empty()) {
      rejected += (rejected.empty() ? "" : "; ") + name + " lacks " + missing;
      continue;
    }
    const int rank = preference(properties.properties.deviceType);
    if (best && rank >= best_preference) continue;
    PhysicalDeviceChoice choice;
    choice.handle = device;
    choice.compute_queue_family = *compute_queue_family(device);
    choice.description.device_name = name;
    choice.description.driver = std::string(driver.driverName) + " (" + driver.driverInfo + ")";
    choice.description.is_cpu = properties.properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
    choice.description.max_storage_buffer_bytes =
        properties.properties.limits.maxStorageBufferRange;
    choice.description.loop_limited = driver.driverID == VK_DRIVER_ID_MESA_LLVMPIPE;
    best = choice;
    best_preference = rank;
  }
  if (!best) {
    if (!rejected.empty()) {
      reason = "no usable Vulkan device: " + rejected;
    } else {
      reason =
          std::string("no Vulkan device matches POSEKIT_VULKAN_DEVICE=") + (wanted ? wanted : "");
    }
  }
  return best;
}

Discovery discover_device() {
  Discovery discovery;
  VkApplicationInfo application{};
  application.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
  application.pApplicationName = "posekit";
  application.apiVersion = VK_API_VERSION_1_2;
  VkInstanceCreateInfo create_info{};
  create_info.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
  create_info.pApplicationInfo = &application;
  VkInstance instance = VK_NULL_HANDLE;
  const VkResult created = vkCreateInstance(&create_info, nullptr, &instance);
  if (created != VK_SUCCESS) {
    discovery.reason = "vkCreateInstance failed with " + result_name(created) +
                       ": no Vulkan driver installed (e.g. mesa-vulkan-drivers)";
    return discovery;
  }
  ScopedInstance instance_guard(instance);
  try {
    std::string reason;
    if (const auto choice = choose_physical_device(instance, reason)) {
      discovery.device = choice->description;
    } else {
      discovery.reason = reason;
    }
  } catch (const std::exception& error) {
    discovery.reason = error.what();
  }
  return discovery;
}

}  // namespace posekit::vulkan
