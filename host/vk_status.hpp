// SPDX-License-Identifier: MIT
// The one place a VkResult becomes a Status (STYLE.md: convert VkResult in exactly one function).
#pragma once

#include <vulkan/vulkan.h>

#include "engine/core/result.hpp"
#include "engine/core/status.hpp"

namespace odeskin::vk {

// Ok for VK_SUCCESS (and the non-error codes VK_INCOMPLETE etc.). kUnavailable when the driver or
// loader is missing or refuses to start (INITIALIZATION_FAILED, INCOMPATIBLE_DRIVER, a missing
// layer/extension/feature), so callers can skip or fall back to the CPU; kDeviceError naming `what`
// for every other failure (out of memory, device lost, ...).
Status vkStatus(VkResult result, const char* what);

// Name of a VkResult ("VK_ERROR_DEVICE_LOST"), for messages.
const char* vkResultName(VkResult result);

}  // namespace odeskin::vk

// Returns the converted Status from the enclosing function when the Vulkan call fails; the call's
// text names the failing step in the message.
#define ODESKIN_VK_TRY(call) ODESKIN_TRY(::odeskin::vk::vkStatus((call), #call))
