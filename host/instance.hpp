// SPDX-License-Identifier: MIT
// VkInstance owner: API 1.1, the Khronos validation layer when asked for and installed, and a
// VK_EXT_debug_utils messenger that records warnings and errors so tests can fail on any of them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "engine/core/result.hpp"

namespace odeskin::vk {

// Warnings and errors reported by the validation layer (and the loader) through debug utils.
// Thread-safe: drivers may call back from any thread.
class DebugLog {
 public:
  void add(std::string message);
  std::size_t count() const;
  std::vector<std::string> messages() const;
  void clear();

 private:
  mutable std::mutex mutex_;
  std::vector<std::string> messages_;
};

// What to do when the loader finds no driver or no device (both errors end with it).
inline constexpr const char* kInstallDriverHint =
    "install mesa-vulkan-drivers for lavapipe (a CPU implementation), or a GPU driver; VK_DRIVER_FILES can "
    "point the loader at an ICD json";

struct InstanceOptions {
  // Enable VK_LAYER_KHRONOS_validation if it is installed (silently off otherwise; see
  // Instance::validationEnabled). The environment variable ODESKIN_VALIDATION=1 also turns it on.
  bool validation = false;
  // With validation, also its synchronization checks (hazards between commands that lack a
  // barrier), which the layer leaves off unless asked.
  bool sync_validation = true;
  // Optional caller-owned log that must outlive the Instance; lets a test read messages emitted
  // while the instance itself is being destroyed. Null: the Instance owns its log.
  DebugLog* debug_log = nullptr;
  const char* application_name = "odeskin";
};

class Instance {
 public:
  // kUnavailable when no Vulkan loader/driver can create an instance (VK_ERROR_INCOMPATIBLE_DRIVER),
  // kDeviceError for other failures.
  static Result<Instance> create(const InstanceOptions& options = {});

  // True when VK_LAYER_KHRONOS_validation is listed by the loader.
  static bool validationLayerInstalled();
  // True when ODESKIN_VALIDATION is set to a value other than "0" or empty.
  static bool validationRequestedByEnvironment();

  Instance(Instance&& other) noexcept;
  Instance& operator=(Instance&& other) noexcept;
  Instance(const Instance&) = delete;
  Instance& operator=(const Instance&) = delete;
  ~Instance();

  VkInstance handle() const { return instance_; }
  // Instance-level API version the loader supports (vkEnumerateInstanceVersion).
  std::uint32_t loaderApiVersion() const { return loader_api_version_; }
  bool validationEnabled() const { return validation_enabled_; }
  bool syncValidationEnabled() const { return sync_validation_; }
  // Warnings and errors seen so far (validation on or not: the loader reports through it too).
  const DebugLog& debugLog() const { return *log_; }
  DebugLog& debugLog() { return *log_; }

 private:
  Instance() = default;
  void destroy();

  std::unique_ptr<DebugLog> owned_log_;  // stable address for the messenger callback
  DebugLog* log_ = nullptr;
  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  std::uint32_t loader_api_version_ = VK_API_VERSION_1_0;
  bool validation_enabled_ = false;
  bool sync_validation_ = false;
};

}  // namespace odeskin::vk
