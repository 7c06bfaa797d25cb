// SPDX-License-Identifier: MIT
#include "vk_status.hpp"

#include <string>

namespace odeskin::vk {

const char* vkResultName(VkResult result) {
  switch (result) {
#define ODESKIN_VK_CASE(name) \
  case name:                  \
    return #name;
    ODESKIN_VK_CASE(VK_SUCCESS)
    ODESKIN_VK_CASE(VK_NOT_READY)
    ODESKIN_VK_CASE(VK_TIMEOUT)
    ODESKIN_VK_CASE(VK_INCOMPLETE)
    ODESKIN_VK_CASE(VK_ERROR_OUT_OF_HOST_MEMORY)
    ODESKIN_VK_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY)
    ODESKIN_VK_CASE(VK_ERROR_INITIALIZATION_FAILED)
    ODESKIN_VK_CASE(VK_ERROR_DEVICE_LOST)
    ODESKIN_VK_CASE(VK_ERROR_MEMORY_MAP_FAILED)
    ODESKIN_VK_CASE(VK_ERROR_LAYER_NOT_PRESENT)
    ODESKIN_VK_CASE(VK_ERROR_EXTENSION_NOT_PRESENT)
    ODESKIN_VK_CASE(VK_ERROR_FEATURE_NOT_PRESENT)
    ODESKIN_VK_CASE(VK_ERROR_INCOMPATIBLE_DRIVER)
    ODESKIN_VK_CASE(VK_ERROR_TOO_MANY_OBJECTS)
    ODESKIN_VK_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED)
    ODESKIN_VK_CASE(VK_ERROR_FRAGMENTED_POOL)
    ODESKIN_VK_CASE(VK_ERROR_OUT_OF_POOL_MEMORY)
    ODESKIN_VK_CASE(VK_ERROR_INVALID_SHADER_NV)
    ODESKIN_VK_CASE(VK_ERROR_UNKNOWN)
#undef ODESKIN_VK_CASE
    default:
      return "VkResult (unlisted)";
  }
}

Status vkStatus(VkResult result, const char* what) {
  // Positive codes (VK_INCOMPLETE, VK_NOT_READY, VK_TIMEOUT) are not failures; callers that care
  // about them test the VkResult themselves before converting.
  if (result >= 0) return okStatus();
  std::string message = std::string(what) + " failed: " + vkResultName(result) + " (" +
                        std::to_string(static_cast<int>(result)) + ")";
  switch (result) {
    case VK_ERROR_INITIALIZATION_FAILED:
    case VK_ERROR_INCOMPATIBLE_DRIVER:
    case VK_ERROR_LAYER_NOT_PRESENT:
    case VK_ERROR_EXTENSION_NOT_PRESENT:
    case VK_ERROR_FEATURE_NOT_PRESENT:
      return unavailable(std::move(message));
    default:
      return deviceError(std::move(message));
  }
}

}  // namespace odeskin::vk
