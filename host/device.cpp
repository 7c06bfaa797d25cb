// SPDX-License-Identifier: MIT
#include "device.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <utility>

#include "fault_injection.hpp"
#include "vk_status.hpp"

namespace odeskin::vk {
namespace {

// Lower rank = preferred by "auto": real GPUs first, lavapipe (CPU) last.
int typeRank(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 0;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 1;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    case VK_PHYSICAL_DEVICE_TYPE_OTHER: return 3;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return 4;
    default: return 5;
  }
}

std::string lowerCase(std::string_view text) {
  std::string out(text);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

// On one line, as an error message is ("0: llvmpipe (CPU); 1: ...").
std::string deviceList(const std::vector<VkPhysicalDevice>& devices) {
  std::string list;
  for (std::size_t i = 0; i < devices.size(); ++i) {
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(devices[i], &p);
    list += (i == 0 ? " " : "; ") + std::to_string(i) + ": " + p.deviceName + " (" + deviceTypeName(p.deviceType) + ")";
  }
  return list;
}

}  // namespace

const char* deviceTypeName(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete GPU";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated GPU";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual GPU";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "CPU";
    default: return "other";
  }
}

Result<std::vector<VkPhysicalDevice>> physicalDevices(const Instance& instance) {
  std::uint32_t count = 0;
  ODESKIN_VK_TRY(vkEnumeratePhysicalDevices(instance.handle(), &count, nullptr));
  std::vector<VkPhysicalDevice> devices(count);
  if (count > 0) ODESKIN_VK_TRY(vkEnumeratePhysicalDevices(instance.handle(), &count, devices.data()));
  devices.resize(count);
  if (injectedFault() == VkFault::kNoDevice) devices.clear();
  if (devices.empty()) {
    return unavailable(std::string("no Vulkan device: ") + kInstallDriverHint);
  }
  return devices;
}

Result<std::uint32_t> selectPhysicalDevice(const Instance& instance, std::string_view selector) {
  ODESKIN_ASSIGN_OR_RETURN(std::vector<VkPhysicalDevice> devices, physicalDevices(instance));
  std::string chosen(selector);
  bool from_env = false;
  if (chosen.empty() || chosen == "auto") {
    const char* env = std::getenv("ODESKIN_DEVICE");
    from_env = env != nullptr && env[0] != '\0';
    chosen = from_env ? env : "auto";
  }
  // Where the selector came from, so the message points at what to change.
  const std::string source = from_env ? "ODESKIN_DEVICE=" + chosen : "--device " + chosen;
  if (chosen == "auto") {
    std::uint32_t best = 0;
    int best_rank = 1 << 30;
    for (std::uint32_t i = 0; i < devices.size(); ++i) {
      VkPhysicalDeviceProperties p;
      vkGetPhysicalDeviceProperties(devices[i], &p);
      if (typeRank(p.deviceType) < best_rank) {
        best_rank = typeRank(p.deviceType);
        best = i;
      }
    }
    return best;
  }
  if (std::all_of(chosen.begin(), chosen.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); })) {
    // More than 9 digits cannot be a device index and would overflow stoul on 32-bit longs.
    if (chosen.size() < 10 && std::stoul(chosen) < devices.size()) {
      return static_cast<std::uint32_t>(std::stoul(chosen));
    }
    return unavailable(source + ": no device with that index; available devices:" + deviceList(devices));
  }
  std::string needle = lowerCase(chosen);
  for (std::uint32_t i = 0; i < devices.size(); ++i) {
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(devices[i], &p);
    if (lowerCase(p.deviceName).find(needle) != std::string::npos) return i;
  }
  return unavailable(source + ": no Vulkan device name contains \"" + chosen + "\"; available devices:" +
                     deviceList(devices));
}

Result<Device> Device::create(const Instance& instance, std::string_view selector) {
  ODESKIN_ASSIGN_OR_RETURN(std::uint32_t index, selectPhysicalDevice(instance, selector));
  ODESKIN_ASSIGN_OR_RETURN(std::vector<VkPhysicalDevice> devices, physicalDevices(instance));
  Device device;
  device.index_ = index;
  const std::vector<VkQueueFamilyProperties> families = device.readPhysical(devices[index]);

  // One compute-capable family; among those, prefer one that can write timestamps so GPU times
  // are available (lavapipe has a single GRAPHICS|COMPUTE|TRANSFER family that can).
  int family = -1;
  for (std::uint32_t i = 0; i < families.size(); ++i) {
    if (!(families[i].queueFlags & VK_QUEUE_COMPUTE_BIT)) continue;
    if (family < 0 || (families[i].timestampValidBits > 0 &&
                       families[static_cast<std::uint32_t>(family)].timestampValidBits == 0)) {
      family = static_cast<int>(i);
    }
  }
  if (family < 0) return unavailable(std::string("Vulkan device has no compute queue: ") + device.name());
  device.queue_family_ = static_cast<std::uint32_t>(family);

  // A single queue: every submission is ordered on it, which keeps synchronization simple.
  float priority = 1.0f;
  VkDeviceQueueCreateInfo queue_info{};
  queue_info.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO;
  queue_info.queueFamilyIndex = device.queue_family_;
  queue_info.queueCount = 1;
  queue_info.pQueuePriorities = &priority;
  VkDeviceCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO;
  info.queueCreateInfoCount = 1;
  info.pQueueCreateInfos = &queue_info;
  VkResult created = injectedResult(VkFault::kDeviceCreate);
  if (created == VK_SUCCESS) created = vkCreateDevice(device.physical_, &info, nullptr, &device.device_);
  ODESKIN_TRY(vkStatus(created, "vkCreateDevice"));
  ODESKIN_TRY(device.finish(families, 0));
  return device;
}

Result<Device> Device::adopt(const ExternalDevice& external) {
  if (external.physical_device == VK_NULL_HANDLE || external.device == VK_NULL_HANDLE) {
    return invalidArgument("adopted Vulkan device: the physical device and the device must not be null");
  }
  Device device;
  device.owns_device_ = false;
  device.index_ = UINT32_MAX;
  const std::vector<VkQueueFamilyProperties> families = device.readPhysical(external.physical_device);
  const auto family_count = static_cast<std::uint32_t>(families.size());
  const std::string where = std::string("adopted Vulkan device ") + device.name() + ": queue family " +
                            std::to_string(external.queue_family);
  if (external.queue_family >= family_count) {
    return invalidArgument(where + " does not exist (the device has " + std::to_string(family_count) + ")");
  }
  if (!(families[external.queue_family].queueFlags & VK_QUEUE_COMPUTE_BIT)) {
    return invalidArgument(where + " cannot run compute");
  }
  if (external.queue_index >= families[external.queue_family].queueCount) {
    return invalidArgument(where + " has " + std::to_string(families[external.queue_family].queueCount) +
                           " queues, not queue " + std::to_string(external.queue_index));
  }
  device.queue_family_ = external.queue_family;
  device.device_ = external.device;
  ODESKIN_TRY(device.finish(families, external.queue_index));
  return device;
}

std::vector<VkQueueFamilyProperties> Device::readPhysical(VkPhysicalDevice physical) {
  physical_ = physical;
  vkGetPhysicalDeviceProperties(physical_, &properties_);
  vkGetPhysicalDeviceMemoryProperties(physical_, &memory_);
  std::uint32_t family_count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(physical_, &family_count, nullptr);
  std::vector<VkQueueFamilyProperties> families(family_count);
  vkGetPhysicalDeviceQueueFamilyProperties(physical_, &family_count, families.data());
  return families;
}

Status Device::finish(const std::vector<VkQueueFamilyProperties>& families, std::uint32_t queue_index) {
  timestamp_valid_bits_ = families[queue_family_].timestampValidBits;
  queue_flags_ = families[queue_family_].queueFlags;
  vkGetDeviceQueue(device_, queue_family_, queue_index, &queue_);

  // An in-memory cache shares compiled pipelines between dispatchers built on this device.
  VkPipelineCacheCreateInfo cache_info{};
  cache_info.sType = VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO;
  VkPipelineCache cache = VK_NULL_HANDLE;
  ODESKIN_VK_TRY(vkCreatePipelineCache(device_, &cache_info, nullptr, &cache));
  pipeline_cache_ = UniquePipelineCache(device_, cache);
  return okStatus();
}

Device::Device(Device&& other) noexcept { *this = std::move(other); }

Device& Device::operator=(Device&& other) noexcept {
  if (this != &other) {
    destroy();
    physical_ = std::exchange(other.physical_, VK_NULL_HANDLE);
    device_ = std::exchange(other.device_, VK_NULL_HANDLE);
    queue_ = std::exchange(other.queue_, VK_NULL_HANDLE);
    owns_device_ = other.owns_device_;
    index_ = other.index_;
    queue_family_ = other.queue_family_;
    queue_flags_ = other.queue_flags_;
    timestamp_valid_bits_ = other.timestamp_valid_bits_;
    properties_ = other.properties_;
    memory_ = other.memory_;
    pipeline_cache_ = std::move(other.pipeline_cache_);
    queue_mutex_ = std::move(other.queue_mutex_);
  }
  return *this;
}

Device::~Device() { destroy(); }

void Device::destroy() {
  if (device_ == VK_NULL_HANDLE) return;
  // Children before the device; idle first so no command buffer from the pool is still running.
  // An adopted device is the application's: only odeskin's queue is waited for, and it stays.
  if (owns_device_) {
    vkDeviceWaitIdle(device_);
  } else if (queue_ != VK_NULL_HANDLE) {
    (void)waitQueueIdle();  // a lost device leaves nothing better to do than to go on destroying
  }
  pipeline_cache_.reset();
  if (owns_device_) vkDestroyDevice(device_, nullptr);
  device_ = VK_NULL_HANDLE;
}

Result<std::uint32_t> Device::findMemoryType(std::uint32_t type_bits, VkMemoryPropertyFlags required,
                                             VkMemoryPropertyFlags preferred) const {
  int fallback = -1;
  for (std::uint32_t i = 0; i < memory_.memoryTypeCount; ++i) {
    if (!(type_bits & (1u << i))) continue;
    VkMemoryPropertyFlags flags = memory_.memoryTypes[i].propertyFlags;
    if ((flags & required) != required) continue;
    if ((flags & preferred) == preferred) return i;
    if (fallback < 0) fallback = static_cast<int>(i);
  }
  if (fallback >= 0) return static_cast<std::uint32_t>(fallback);
  return unavailable("no Vulkan memory type with the required properties on " + std::string(name()));
}

Status Device::submit(const VkSubmitInfo& info, VkFence fence) const {
  const std::lock_guard lock(*queue_mutex_);
  VkResult submitted = injectedResult(VkFault::kDeviceLost);
  if (submitted == VK_SUCCESS) submitted = vkQueueSubmit(queue_, 1, &info, fence);
  return vkStatus(submitted, "vkQueueSubmit");
}

Status Device::waitQueueIdle() const {
  const std::lock_guard lock(*queue_mutex_);
  return vkStatus(vkQueueWaitIdle(queue_), "vkQueueWaitIdle");
}

Result<UniqueCommandPool> Device::createCommandPool(VkCommandPoolCreateFlags flags) const {
  VkCommandPoolCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
  info.flags = flags;
  info.queueFamilyIndex = queue_family_;
  VkCommandPool pool = VK_NULL_HANDLE;
  ODESKIN_VK_TRY(vkCreateCommandPool(device_, &info, nullptr, &pool));
  return UniqueCommandPool(device_, pool);
}

Result<VkCommandBuffer> Device::allocateCommandBuffer(VkCommandPool pool) const {
  VkCommandBufferAllocateInfo alloc{};
  alloc.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
  alloc.commandPool = pool;
  alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  alloc.commandBufferCount = 1;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  ODESKIN_VK_TRY(vkAllocateCommandBuffers(device_, &alloc, &cmd));
  return cmd;
}

Result<UniqueFence> Device::createFence() const {
  VkFenceCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
  VkFence fence = VK_NULL_HANDLE;
  ODESKIN_VK_TRY(vkCreateFence(device_, &info, nullptr, &fence));
  return UniqueFence(device_, fence);
}

Status Device::submitAndWait(const std::function<void(VkCommandBuffer)>& record) const {
  // A pool per call: two threads uploading on one device must not share one (uploads are rare).
  ODESKIN_ASSIGN_OR_RETURN(const UniqueCommandPool pool, createCommandPool(VK_COMMAND_POOL_CREATE_TRANSIENT_BIT));
  ODESKIN_ASSIGN_OR_RETURN(VkCommandBuffer cmd, allocateCommandBuffer(pool.get()));

  VkCommandBufferBeginInfo begin{};
  begin.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  ODESKIN_VK_TRY(vkBeginCommandBuffer(cmd, &begin));
  record(cmd);
  ODESKIN_VK_TRY(vkEndCommandBuffer(cmd));

  // A fence, not vkQueueWaitIdle, so per-frame work already on the queue is not waited for twice.
  ODESKIN_ASSIGN_OR_RETURN(const UniqueFence fence, createFence());
  VkFence fence_handle = fence.get();
  VkSubmitInfo submit{};
  submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &cmd;
  ODESKIN_TRY(this->submit(submit, fence.get()));
  ODESKIN_VK_TRY(vkWaitForFences(device_, 1, &fence_handle, VK_TRUE, UINT64_MAX));
  return okStatus();
}

Result<Gpu> Gpu::open(std::string_view selector, bool validation) {
  InstanceOptions options;
  options.validation = validation;
  ODESKIN_ASSIGN_OR_RETURN(Instance instance, Instance::create(options));
  ODESKIN_ASSIGN_OR_RETURN(Device device, Device::create(instance, selector));
  return Gpu{std::move(instance), std::move(device)};
}

}  // namespace odeskin::vk
