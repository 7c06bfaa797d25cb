// SPDX-License-Identifier: MIT
#include "device_info.hpp"

#include <cstring>
#include <utility>

#include "device.hpp"

namespace odeskin::vk {
namespace {

std::string versionString(std::uint32_t v) {
  return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v)) + "." +
         std::to_string(VK_API_VERSION_PATCH(v));
}

std::string memoryTypeFlags(VkMemoryPropertyFlags flags) {
  static constexpr std::pair<VkMemoryPropertyFlags, const char*> kNames[] = {
      {VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, "device-local"},
      {VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT, "host-visible"},
      {VK_MEMORY_PROPERTY_HOST_COHERENT_BIT, "coherent"},
      {VK_MEMORY_PROPERTY_HOST_CACHED_BIT, "cached"},
      {VK_MEMORY_PROPERTY_LAZILY_ALLOCATED_BIT, "lazy"},
      {VK_MEMORY_PROPERTY_PROTECTED_BIT, "protected"},
  };
  std::string text;
  for (const auto& [bit, name] : kNames) {
    if ((flags & bit) == 0) continue;
    if (!text.empty()) text += '+';
    text += name;
  }
  return text.empty() ? "none" : text;
}

}  // namespace

Result<std::vector<DeviceInfo>> queryDeviceInfo(const Instance& instance) {
  ODESKIN_ASSIGN_OR_RETURN(std::vector<VkPhysicalDevice> devices, physicalDevices(instance));
  std::vector<DeviceInfo> infos;
  for (std::uint32_t i = 0; i < devices.size(); ++i) {
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(devices[i], &p);
    DeviceInfo info;
    info.index = i;
    info.name = p.deviceName;
    info.type = deviceTypeName(p.deviceType);
    info.api_version = p.apiVersion;
    // Driver name/info is core in 1.2; older devices simply leave it blank.
    if (p.apiVersion >= VK_API_VERSION_1_2) {
      VkPhysicalDeviceDriverProperties driver{};
      driver.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES;
      VkPhysicalDeviceProperties2 p2{};
      p2.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2;
      p2.pNext = &driver;
      vkGetPhysicalDeviceProperties2(devices[i], &p2);
      info.driver_name = driver.driverName;
      info.driver_info = driver.driverInfo;
    }
    const VkPhysicalDeviceLimits& l = p.limits;
    std::memcpy(info.max_compute_work_group_size, l.maxComputeWorkGroupSize, sizeof(info.max_compute_work_group_size));
    info.max_compute_work_group_invocations = l.maxComputeWorkGroupInvocations;
    info.max_storage_buffer_range = l.maxStorageBufferRange;
    info.max_push_constants_size = l.maxPushConstantsSize;
    info.timestamp_period_ns = l.timestampPeriod;
    info.timestamp_compute_and_graphics = l.timestampComputeAndGraphics == VK_TRUE;
    VkPhysicalDeviceMemoryProperties memory;
    vkGetPhysicalDeviceMemoryProperties(devices[i], &memory);
    for (std::uint32_t h = 0; h < memory.memoryHeapCount; ++h) {
      info.heaps.push_back({memory.memoryHeaps[h].size,
                            (memory.memoryHeaps[h].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT) != 0, {}});
    }
    for (std::uint32_t t = 0; t < memory.memoryTypeCount; ++t) {
      const VkMemoryType& type = memory.memoryTypes[t];
      if (type.heapIndex < info.heaps.size()) info.heaps[type.heapIndex].types.push_back(memoryTypeFlags(type.propertyFlags));
    }
    infos.push_back(std::move(info));
  }
  return infos;
}

Status printDeviceInfo(std::ostream& out, std::string_view selector) {
  ODESKIN_ASSIGN_OR_RETURN(Instance instance, Instance::create());
  out << "Vulkan loader/instance API " << versionString(instance.loaderApiVersion()) << "\n";
  ODESKIN_ASSIGN_OR_RETURN(std::vector<DeviceInfo> infos, queryDeviceInfo(instance));
  Result<std::uint32_t> selected = selectPhysicalDevice(instance, selector);
  for (const DeviceInfo& d : infos) {
    bool chosen = selected.ok() && *selected == d.index;
    out << (chosen ? "* " : "  ") << "device " << d.index << ": " << d.name << " (" << d.type << ")"
        << (chosen ? "  <- selected" : "") << "\n";
    out << "    driver: " << (d.driver_name.empty() ? "?" : d.driver_name) << " "
        << d.driver_info << ", API " << versionString(d.api_version) << "\n";
    out << "    maxComputeWorkGroupSize: " << d.max_compute_work_group_size[0] << " x "
        << d.max_compute_work_group_size[1] << " x " << d.max_compute_work_group_size[2]
        << ", maxComputeWorkGroupInvocations: " << d.max_compute_work_group_invocations << "\n";
    out << "    maxStorageBufferRange: " << d.max_storage_buffer_range << " bytes ("
        << d.max_storage_buffer_range / (1024 * 1024) << " MiB), maxPushConstantsSize: "
        << d.max_push_constants_size << " bytes\n";
    out << "    timestampPeriod: " << d.timestamp_period_ns << " ns, timestampComputeAndGraphics: "
        << (d.timestamp_compute_and_graphics ? "yes" : "no") << "\n";
    for (std::size_t h = 0; h < d.heaps.size(); ++h) {
      out << "    heap " << h << ": " << d.heaps[h].size_bytes / (std::uint64_t{1024} * 1024) << " MiB"
          << (d.heaps[h].device_local ? " device-local" : "");
      const char* separator = "; memory types: ";
      for (const std::string& type : d.heaps[h].types) {
        out << separator << type;
        separator = ", ";
      }
      out << "\n";
    }
  }
  if (!selected.ok()) return selected.status();
  return okStatus();
}

}  // namespace odeskin::vk
