#include "vulkan_validation.hpp"

#include <posekit/error.hpp>

#include <cstdlib>
#include <cstring>
#include <iostream>
#include <mutex>

namespace posekit::vulkan {
namespace {

struct MessageLog {
  std::mutex mutex;
  std::vector<std::string> messages;
};

// Never destroyed: messages may arrive while static objects (devices held by tests) are torn
// down at exit.
MessageLog& message_log() {
  static auto* log = new MessageLog;
  return *log;
}

VKAPI_ATTR VkBool32 VKAPI_CALL record_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                              VkDebugUtilsMessageTypeFlagsEXT /*types*/,
                                              const VkDebugUtilsMessengerCallbackDataEXT* data,
                                              void* /*user_data*/) {
  const char* level =
      (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) != 0 ? "error" : "warning";
  std::string message = std::string(level) + ": ";
  if (data != nullptr && data->pMessageIdName != nullptr)
    message += std::string(data->pMessageIdName) + ": ";
  message += data != nullptr && data->pMessage != nullptr ? data->pMessage : "(no text)";
  for (char& c : message) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  std::cerr << "posekit: Vulkan validation " << message << "\n";
  MessageLog& log = message_log();
  const std::lock_guard<std::mutex> lock(log.mutex);
  log.messages.push_back(std::move(message));
  // VK_FALSE: the call that triggered the message goes on, as the specification requires.
  return VK_FALSE;
}

}  // namespace

bool validation_requested() {
  const char* value = std::getenv("POSEKIT_VULKAN_VALIDATION");
  if (value == nullptr) return false;
  for (const char* off : {"", "0", "off", "false", "no"}) {
    if (std::strcmp(value, off) == 0) return false;
  }
  return true;
}

bool validation_layer_installed() {
  std::uint32_t count = 0;
  if (vkEnumerateInstanceLayerProperties(&count, nullptr) != VK_SUCCESS) return false;
  std::vector<VkLayerProperties> layers(count);
  if (vkEnumerateInstanceLayerProperties(&count, layers.data()) < 0) return false;
  layers.resize(count);
  for (const VkLayerProperties& layer : layers) {
    if (std::strcmp(layer.layerName, kValidationLayerName) == 0) return true;
  }
  return false;
}

std::string missing_validation_layer_reason() {
  return std::string("POSEKIT_VULKAN_VALIDATION asks for ") + kValidationLayerName +
         ", which the Vulkan loader does not find (install vulkan-validationlayers or point "
         "VK_LAYER_PATH at the folder of its .json manifest)";
}

std::size_t validation_message_count() {
  MessageLog& log = message_log();
  const std::lock_guard<std::mutex> lock(log.mutex);
  return log.messages.size();
}

std::vector<std::string> validation_messages_since(std::size_t first) {
  MessageLog& log = message_log();
  const std::lock_guard<std::mutex> lock(log.mutex);
  if (first >= log.messages.size()) return {};
  return {log.messages.begin() + static_cast<std::ptrdiff_t>(first), log.messages.end()};
}

void throw_if_validation_messages(std::size_t first, const std::string& operation) {
  const std::vector<std::string> messages = validation_messages_since(first);
  if (messages.empty()) return;
  throw DeviceError("Vulkan validation reported " + std::to_string(messages.size()) +
                    " message(s) during " + operation + "; the first: " + messages.front());
}

VkDebugUtilsMessengerCreateInfoEXT validation_messenger_info() {
  VkDebugUtilsMessengerCreateInfoEXT info{};
  info.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT;
  info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                         VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                     VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                     VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  info.pfnUserCallback = record_message;
  return info;
}

}  // namespace posekit::vulkan
