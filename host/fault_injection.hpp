// SPDX-License-Identifier: MIT
// A test hook, not a feature: ODESKIN_VK_FAULT makes one kind of Vulkan call fail the way a broken
// driver or a full or lost GPU would, so the commands' error and CPU-fallback paths can be tested on
// a machine whose device works. Unset (the normal case) every call below goes to the driver unchanged.
//   no-device      vkEnumeratePhysicalDevices reports no device
//   device-create  vkCreateDevice returns VK_ERROR_INITIALIZATION_FAILED
//   out-of-memory  vkAllocateMemory returns VK_ERROR_OUT_OF_DEVICE_MEMORY
//   device-lost    vkQueueSubmit returns VK_ERROR_DEVICE_LOST
// Any other value is ignored (and reported once on stderr) rather than failing everything.
#pragma once

#include <vulkan/vulkan.h>

namespace odeskin::vk {

enum class VkFault { kNone, kNoDevice, kDeviceCreate, kOutOfMemory, kDeviceLost };

// The fault ODESKIN_VK_FAULT asks for, read once per process.
VkFault injectedFault();

// The VkResult the call guarded by `site` must return instead of calling the driver, or VK_SUCCESS
// when that fault is not injected (then the caller makes the real call).
VkResult injectedResult(VkFault site);

}  // namespace odeskin::vk
