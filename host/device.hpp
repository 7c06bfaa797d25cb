// SPDX-License-Identifier: MIT
// Physical device selection and the logical device: one compute queue, a command pool for one-off
// and per-frame command buffers, and a pipeline cache.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include <vulkan/vulkan.h>

#include "engine/core/result.hpp"
#include "instance.hpp"
#include "vk_handle.hpp"

namespace odeskin::vk {

// All physical devices in loader order (the order `odeskin info` numbers them).
// kUnavailable when there is none, with a hint to install lavapipe.
Result<std::vector<VkPhysicalDevice>> physicalDevices(const Instance& instance);

// Index into physicalDevices() that `selector` picks:
//  - "auto" or empty: the environment variable ODESKIN_DEVICE if set, else the first discrete GPU,
//    then integrated, virtual, other, and finally CPU devices (lavapipe);
//  - a decimal number: that index;
//  - anything else: the first device whose name contains it, ignoring case.
// kUnavailable when there are no devices, and when the index or the name matches none: the
// message names the selector's source ("--device X" or "ODESKIN_DEVICE=X") and lists every device.
// (Unavailable, not a bad argument: a device named for one machine is missing on another, and
// `--backend auto` then uses the CPU with a note, as for a machine without Vulkan.)
Result<std::uint32_t> selectPhysicalDevice(const Instance& instance, std::string_view selector);

// "discrete GPU", "integrated GPU", "virtual GPU", "CPU", "other".
const char* deviceTypeName(VkPhysicalDeviceType type);

// A device the application created and keeps: a game engine's own VkDevice, so that the runtime's
// output buffers live where its renderer binds vertex buffers (docs/runtime.md). odeskin needs no
// device feature or extension beyond Vulkan 1.1 core.
struct ExternalDevice {
  VkPhysicalDevice physical_device = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;      // created from physical_device through the Vulkan loader
  std::uint32_t queue_family = 0;        // must support compute
  std::uint32_t queue_index = 0;         // within the family, as created
};

class Device {
 public:
  // Selects a physical device (see selectPhysicalDevice) and creates a logical device with one
  // compute-capable queue. kUnavailable when the device has no compute queue.
  static Result<Device> create(const Instance& instance, std::string_view selector = "auto");

  // Wraps an application's device without owning it: odeskin creates its pipeline cache there (and
  // its runtimes their command pools) and submits to that queue. Vulkan requires the application
  // not to use the queue from another thread during odeskin's calls that submit
  // (DeformRuntime::submitFrame, the uploads of create()) or wait. Destroying the wrapper waits for
  // that queue to idle and destroys odeskin's cache, never the device. kInvalidArgument for null handles, a
  // queue family or index the device does not have, or a family without compute.
  static Result<Device> adopt(const ExternalDevice& external);

  Device(Device&& other) noexcept;
  Device& operator=(Device&& other) noexcept;
  Device(const Device&) = delete;
  Device& operator=(const Device&) = delete;
  ~Device();

  VkDevice handle() const { return device_; }
  VkPhysicalDevice physicalDevice() const { return physical_; }
  std::uint32_t index() const { return index_; }  // into physicalDevices(); UINT32_MAX when adopted
  bool ownsDevice() const { return owns_device_; }
  const char* name() const { return properties_.deviceName; }
  const VkPhysicalDeviceProperties& properties() const { return properties_; }
  const VkPhysicalDeviceLimits& limits() const { return properties_.limits; }
  const VkPhysicalDeviceMemoryProperties& memoryProperties() const { return memory_; }
  VkQueue queue() const { return queue_; }
  std::uint32_t queueFamily() const { return queue_family_; }
  VkQueueFlags queueFlags() const { return queue_flags_; }
  // Bits of a timestamp written on queue(); 0 means the queue cannot time dispatches.
  std::uint32_t timestampValidBits() const { return timestamp_valid_bits_; }
  VkPipelineCache pipelineCache() const { return pipeline_cache_.get(); }

  // Every submission odeskin makes on queue() goes through here: the queue must be used by one
  // thread at a time, and runtimes sharing this device may be driven from different threads.
  // Command pools are the other object Vulkan wants so guarded; odeskin gives each FrameRing and
  // each submitAndWait its own, so none is shared.
  Status submit(const VkSubmitInfo& info, VkFence fence) const;
  // vkQueueWaitIdle on queue(), under the same lock: for work odeskin has no fence of (frames an
  // engine submitted in its own command buffers).
  Status waitQueueIdle() const;

  // Index of a memory type allowed by `type_bits` that has all `required` flags, preferring one
  // that also has all `preferred` flags. kUnavailable when none has the required flags.
  Result<std::uint32_t> findMemoryType(std::uint32_t type_bits, VkMemoryPropertyFlags required,
                                       VkMemoryPropertyFlags preferred) const;

  // A command pool on queue()'s family, for one user at a time (a FrameRing, one submitAndWait).
  Result<UniqueCommandPool> createCommandPool(VkCommandPoolCreateFlags flags) const;
  // A primary command buffer from `pool` (freed with the pool), and an unsignalled fence.
  Result<VkCommandBuffer> allocateCommandBuffer(VkCommandPool pool) const;
  Result<UniqueFence> createFence() const;

  // Records `record` into a one-off command buffer (from a pool of its own), submits it and waits
  // for it (uploads, readbacks, tests). Not for the per-frame path.
  Status submitAndWait(const std::function<void(VkCommandBuffer)>& record) const;

 private:
  Device() = default;
  void destroy();
  // Sets physical_, its properties and memory; returns its queue families.
  std::vector<VkQueueFamilyProperties> readPhysical(VkPhysicalDevice physical);
  // The queue's family facts, the queue and the pipeline cache, once device_ exists.
  Status finish(const std::vector<VkQueueFamilyProperties>& families, std::uint32_t queue_index);

  VkPhysicalDevice physical_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  bool owns_device_ = true;
  std::uint32_t index_ = 0;
  std::uint32_t queue_family_ = 0;
  VkQueueFlags queue_flags_ = 0;
  std::uint32_t timestamp_valid_bits_ = 0;
  VkPhysicalDeviceProperties properties_{};
  VkPhysicalDeviceMemoryProperties memory_{};
  UniquePipelineCache pipeline_cache_;
  std::unique_ptr<std::mutex> queue_mutex_ = std::make_unique<std::mutex>();  // movable Device
};

// An instance and a device opened together; members in destruction order (device first).
struct Gpu {
  Instance instance;
  Device device;

  // `validation`: as InstanceOptions::validation. Errors as Instance::create and Device::create.
  static Result<Gpu> open(std::string_view selector = "auto", bool validation = false);
};

}  // namespace odeskin::vk
