// The Khronos validation layer as posekit uses it: switched on by POSEKIT_VULKAN_VALIDATION, its
// warnings and errors collected in a process-wide log through a debug-utils messenger, and every
// device operation turned into a DeviceError when the layer said anything while it ran.
#pragma once

#include <vulkan/vulkan.h>

#include <cstddef>
#include <string>
#include <vector>

namespace posekit::vulkan {

/// The layer's name.
inline constexpr const char* kValidationLayerName = "VK_LAYER_KHRONOS_validation";

/// True when the environment variable POSEKIT_VULKAN_VALIDATION is set to anything but "", "0",
/// "off", "false" or "no".
bool validation_requested();

/// Whether the Vulkan loader finds the validation layer (installed manifest or VK_LAYER_PATH).
bool validation_layer_installed();

/// The message a missing layer produces when validation was requested.
std::string missing_validation_layer_reason();

/// Number of validation messages (warnings and errors) recorded in this process so far, by every
/// instance, including those reported while objects were destroyed.
std::size_t validation_message_count();

/// The messages recorded from index `first` on (first = an earlier validation_message_count()).
std::vector<std::string> validation_messages_since(std::size_t first);

/// Throws DeviceError quoting the first message recorded from index `first` on, with `operation`
/// naming what ran; does nothing when the layer stayed silent.
void throw_if_validation_messages(std::size_t first, const std::string& operation);

/// The messenger's settings: warnings and errors of every type, recorded by the callback above.
VkDebugUtilsMessengerCreateInfoEXT validation_messenger_info();

}  // namespace posekit::vulkan
