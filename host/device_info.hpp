// SPDX-License-Identifier: MIT
// What `odeskin info` prints: the loader version and, per Vulkan device, the properties and limits
// that decide whether and how fast the deformer runs there.
#pragma once

#include <cstdint>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "engine/core/result.hpp"
#include "instance.hpp"

namespace odeskin::vk {

struct MemoryHeapInfo {
  std::uint64_t size_bytes = 0;
  bool device_local = false;
  // The heap's memory types, each as its property flags ("device-local+host-visible+coherent"):
  // which buffers odeskin maps and which it stages (buffer.hpp) follows from them.
  std::vector<std::string> types;
};

struct DeviceInfo {
  std::uint32_t index = 0;
  std::string name;
  std::string type;            // deviceTypeName()
  std::string driver_name;     // VkPhysicalDeviceDriverProperties (empty before Vulkan 1.2)
  std::string driver_info;
  std::uint32_t api_version = 0;
  std::uint32_t max_compute_work_group_size[3] = {0, 0, 0};
  std::uint32_t max_compute_work_group_invocations = 0;
  std::uint32_t max_storage_buffer_range = 0;
  std::uint32_t max_push_constants_size = 0;
  float timestamp_period_ns = 0.0f;
  bool timestamp_compute_and_graphics = false;
  std::vector<MemoryHeapInfo> heaps;
};

// One entry per physical device, in physicalDevices() order. kUnavailable without devices.
Result<std::vector<DeviceInfo>> queryDeviceInfo(const Instance& instance);

// Opens its own instance (no validation) and prints the loader API version and every device,
// marking the one `selector` picks (selectPhysicalDevice rules). Errors as Instance::create and
// selectPhysicalDevice; the device list is printed before a bad-selector error is returned.
Status printDeviceInfo(std::ostream& out, std::string_view selector = "auto");

}  // namespace odeskin::vk
