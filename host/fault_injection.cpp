// SPDX-License-Identifier: MIT
#include "fault_injection.hpp"

#include <cstdio>
#include <cstdlib>
#include <string_view>

namespace odeskin::vk {
namespace {

VkFault parseFault() {
  const char* value = std::getenv("ODESKIN_VK_FAULT");
  if (value == nullptr || value[0] == '\0') return VkFault::kNone;
  const std::string_view text(value);
  if (text == "no-device") return VkFault::kNoDevice;
  if (text == "device-create") return VkFault::kDeviceCreate;
  if (text == "out-of-memory") return VkFault::kOutOfMemory;
  if (text == "device-lost") return VkFault::kDeviceLost;
  std::fprintf(stderr,
               "odeskin: warning: ODESKIN_VK_FAULT=%s ignored (no-device, device-create, out-of-memory or "
               "device-lost)\n",
               value);
  return VkFault::kNone;
}

}  // namespace

VkFault injectedFault() {
  static const VkFault fault = parseFault();
  return fault;
}

VkResult injectedResult(VkFault site) {
  if (site == VkFault::kNone || injectedFault() != site) return VK_SUCCESS;
  switch (site) {
    case VkFault::kDeviceCreate: return VK_ERROR_INITIALIZATION_FAILED;
    case VkFault::kOutOfMemory: return VK_ERROR_OUT_OF_DEVICE_MEMORY;
    case VkFault::kDeviceLost: return VK_ERROR_DEVICE_LOST;
    case VkFault::kNoDevice:  // a count, not a result: physicalDevices() reports zero devices
    case VkFault::kNone: break;
  }
  return VK_SUCCESS;
}

}  // namespace odeskin::vk
