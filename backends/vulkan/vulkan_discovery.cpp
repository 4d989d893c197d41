#include "vulkan_discovery.hpp"

#include <vulkan/vulkan.h>

#include <cstdlib>
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

}  // namespace

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
    discovery.reason = "vkCreateInstance failed (VkResult " + std::to_string(created) +
                       "): no Vulkan driver installed (e.g. mesa-vulkan-drivers)";
    return discovery;
  }
  ScopedInstance instance_guard(instance);

  uint32_t count = 0;
  vkEnumeratePhysicalDevices(instance, &count, nullptr);
  std::vector<VkPhysicalDevice> devices(count);
  if (count > 0) vkEnumeratePhysicalDevices(instance, &count, devices.data());
  if (devices.empty()) {
    discovery.reason = "no Vulkan physical device found";
    return discovery;
  }

  const char* wanted = std::getenv("POSEKIT_VULKAN_DEVICE");
  std::string without_fp64;
  std::string too_old;
  for (VkPhysicalDevice device : devices) {
    VkPhysicalDeviceDriverProperties driver{};
    driver.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES;
    VkPhysicalDeviceProperties2 properties{};
    properties.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2;
    properties.pNext = &driver;
    vkGetPhysicalDeviceProperties2(device, &properties);
    const std::string name = properties.properties.deviceName;
    if (wanted != nullptr && name.find(wanted) == std::string::npos) continue;
    if (properties.properties.apiVersion < VK_API_VERSION_1_2) {
      too_old = name;
      continue;
    }
    VkPhysicalDeviceFeatures features{};
    vkGetPhysicalDeviceFeatures(device, &features);
    if (features.shaderFloat64 != VK_TRUE) {
      without_fp64 = name;
      continue;
    }
    const bool is_cpu = properties.properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
    if (discovery.device && !(discovery.device->is_cpu && !is_cpu)) continue;
    DiscoveredDevice found;
    found.device_name = name;
    found.driver = std::string(driver.driverName) + " (" + driver.driverInfo + ")";
    found.is_cpu = is_cpu;
    found.max_storage_buffer_bytes = properties.properties.limits.maxStorageBufferRange;
    discovery.device = found;
  }
  if (!discovery.device) {
    if (!without_fp64.empty()) {
      discovery.reason = "no Vulkan device with shaderFloat64; found without it: " + without_fp64;
    } else if (!too_old.empty()) {
      discovery.reason = "no Vulkan 1.2 device; found an older one: " + too_old;
    } else {
      discovery.reason = std::string("no Vulkan device matches POSEKIT_VULKAN_DEVICE=") + (wanted ? wanted : "");
    }
  }
  return discovery;
}

}  // namespace posekit::vulkan
