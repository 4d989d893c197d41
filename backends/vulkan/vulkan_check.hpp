// Turning a failed Vulkan call into a DeviceError that names the call, the result, the file and
// the line.
#pragma once

#include <posekit/error.hpp>

#include <vulkan/vulkan.h>

#include <string>

namespace posekit::vulkan {

/// The VkResult's enumerator name ("VK_ERROR_OUT_OF_DEVICE_MEMORY"), or its number.
std::string result_name(VkResult result);

/// Throws DeviceError "CALL failed with RESULT (FILE:LINE)" unless result is VK_SUCCESS.
void check(VkResult result, const char* call, const char* file, int line);

}  // namespace posekit::vulkan

#define POSEKIT_VK_CHECK(call) ::posekit::vulkan::check((call), #call, __FILE__, __LINE__)
