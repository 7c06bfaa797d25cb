// SPDX-License-Identifier: MIT
#include "instance.hpp"

#include <cstdlib>
#include <cstring>
#include <utility>

#include "vk_status.hpp"

#if defined(__SANITIZE_ADDRESS__)
// LeakSanitizer reports at exit, after the Vulkan loader has dlclose'd the drivers and layers it
// loaded: their allocations then show as "<unknown module>" and no suppression can name them. So a
// sanitized build keeps every library it loads. This definition takes the loader's dlclose calls
// (the linker exports it because libvulkan.so.1 imports dlclose), and tests/sanitizers/lsan.supp
// names the drivers' own once-per-process allocations by library (docs/reliability.md,
// "Sanitizers").
extern "C" int dlclose(void*) { return 0; }
#endif

namespace odeskin::vk {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

// `layer`: null for the loader's and drivers' extensions, else that layer's.
bool instanceExtensionAvailable(const char* name, const char* layer = nullptr) {
  std::uint32_t count = 0;
  if (vkEnumerateInstanceExtensionProperties(layer, &count, nullptr) != VK_SUCCESS) return false;
  std::vector<VkExtensionProperties> extensions(count);
  if (vkEnumerateInstanceExtensionProperties(layer, &count, extensions.data()) < 0) return false;
  for (const VkExtensionProperties& e : extensions) {
    if (std::strcmp(e.extensionName, name) == 0) return true;
  }
  return false;
}

// Records warnings and errors; returning VK_FALSE tells the layer not to abort the call.
VKAPI_ATTR VkBool32 VKAPI_CALL debugCallback(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                             VkDebugUtilsMessageTypeFlagsEXT /*types*/,
                                             const VkDebugUtilsMessengerCallbackDataEXT* data,
                                             void* user) {
  const char* level = (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) ? "error" : "warning";
  std::string text = std::string(level) + ": " + (data && data->pMessage ? data->pMessage : "(null)");
  static_cast<DebugLog*>(user)->add(std::move(text));
  return VK_FALSE;
}

VkDebugUtilsMessengerCreateInfoEXT messengerInfo(DebugLog* log) {
  VkDebugUtilsMessengerCreateInfoEXT info{};
  info.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT;
  // Warnings count as failures in tests: the layer's warnings are real synchronization or usage bugs.
  info.messageSeverity =
      VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                     VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                     VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  info.pfnUserCallback = debugCallback;
  info.pUserData = log;
  return info;
}

}  // namespace

void DebugLog::add(std::string message) {
  std::lock_guard lock(mutex_);
  messages_.push_back(std::move(message));
}
std::size_t DebugLog::count() const {
  std::lock_guard lock(mutex_);
  return messages_.size();
}
std::vector<std::string> DebugLog::messages() const {
  std::lock_guard lock(mutex_);
  return messages_;
}
void DebugLog::clear() {
  std::lock_guard lock(mutex_);
  messages_.clear();
}

bool Instance::validationLayerInstalled() {
  std::uint32_t count = 0;
  if (vkEnumerateInstanceLayerProperties(&count, nullptr) != VK_SUCCESS) return false;
  std::vector<VkLayerProperties> layers(count);
  if (vkEnumerateInstanceLayerProperties(&count, layers.data()) < 0) return false;
  for (const VkLayerProperties& layer : layers) {
    if (std::strcmp(layer.layerName, kValidationLayer) == 0) return true;
  }
  return false;
}

bool Instance::validationRequestedByEnvironment() {
  const char* value = std::getenv("ODESKIN_VALIDATION");
  return value != nullptr && value[0] != '\0' && std::strcmp(value, "0") != 0;
}

Result<Instance> Instance::create(const InstanceOptions& options) {
  Instance instance;
  if (options.debug_log != nullptr) {
    instance.log_ = options.debug_log;
  } else {
    instance.owned_log_ = std::make_unique<DebugLog>();
    instance.log_ = instance.owned_log_.get();
  }

  // vkEnumerateInstanceVersion exists from loader 1.1 on; its absence means a 1.0 loader, which
  // cannot give us the 1.1 API we ask for below.
  auto enumerate_version = reinterpret_cast<PFN_vkEnumerateInstanceVersion>(
      vkGetInstanceProcAddr(VK_NULL_HANDLE, "vkEnumerateInstanceVersion"));
  if (enumerate_version == nullptr) {
    return unavailable("Vulkan loader only supports API 1.0; odeskin needs 1.1");
  }
  ODESKIN_VK_TRY(enumerate_version(&instance.loader_api_version_));

  bool want_validation = options.validation || validationRequestedByEnvironment();
  instance.validation_enabled_ = want_validation && validationLayerInstalled();
  // The messenger is useful without the layer too (loader errors), whenever the extension exists.
  bool debug_utils = instanceExtensionAvailable(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);

  VkApplicationInfo app{};
  app.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
  app.pApplicationName = options.application_name;
  app.pEngineName = "odeskin";
  // 1.1 is all we need (storage buffers, push constants, timestamps); lavapipe offers 1.3.
  app.apiVersion = VK_API_VERSION_1_1;

  std::vector<const char*> layers;
  if (instance.validation_enabled_) layers.push_back(kValidationLayer);
  std::vector<const char*> extensions;
  if (debug_utils) extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);

  // Chaining the messenger info also reports problems inside vkCreateInstance/vkDestroyInstance.
  VkDebugUtilsMessengerCreateInfoEXT messenger_info = messengerInfo(instance.log_);
  // The layer's synchronization checks (hazards between commands without a barrier), off by default.
  const VkValidationFeatureEnableEXT sync_check = VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
  VkValidationFeaturesEXT features{};
  features.sType = VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT;
  features.pNext = debug_utils ? &messenger_info : nullptr;
  features.enabledValidationFeatureCount = 1;
  features.pEnabledValidationFeatures = &sync_check;
  instance.sync_validation_ = instance.validation_enabled_ && options.sync_validation &&
                              instanceExtensionAvailable(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME, kValidationLayer);
  if (instance.sync_validation_) extensions.push_back(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
  VkInstanceCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
  info.pNext = instance.sync_validation_ ? static_cast<const void*>(&features)
                                         : debug_utils ? static_cast<const void*>(&messenger_info) : nullptr;
  info.pApplicationInfo = &app;
  info.enabledLayerCount = static_cast<std::uint32_t>(layers.size());
  info.ppEnabledLayerNames = layers.data();
  info.enabledExtensionCount = static_cast<std::uint32_t>(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();
  const VkResult created = vkCreateInstance(&info, nullptr, &instance.instance_);
  // The loader's answer when it finds no driver at all: the device check's hint never runs then.
  if (created == VK_ERROR_INCOMPATIBLE_DRIVER) {
    return unavailable(std::string("no Vulkan driver (vkCreateInstance: VK_ERROR_INCOMPATIBLE_DRIVER): ") +
                       kInstallDriverHint);
  }
  ODESKIN_TRY(vk::vkStatus(created, "vkCreateInstance"));

  if (debug_utils) {
    // Extension entry points are not exported by the loader; fetch them through the instance.
    auto create_messenger = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance.instance_, "vkCreateDebugUtilsMessengerEXT"));
    if (create_messenger != nullptr) {
      ODESKIN_VK_TRY(create_messenger(instance.instance_, &messenger_info, nullptr, &instance.messenger_));
    }
  }
  return instance;
}

Instance::Instance(Instance&& other) noexcept { *this = std::move(other); }

Instance& Instance::operator=(Instance&& other) noexcept {
  if (this != &other) {
    destroy();
    owned_log_ = std::move(other.owned_log_);
    log_ = std::exchange(other.log_, nullptr);
    instance_ = std::exchange(other.instance_, VK_NULL_HANDLE);
    messenger_ = std::exchange(other.messenger_, VK_NULL_HANDLE);
    loader_api_version_ = other.loader_api_version_;
    validation_enabled_ = other.validation_enabled_;
    sync_validation_ = other.sync_validation_;
  }
  return *this;
}

Instance::~Instance() { destroy(); }

void Instance::destroy() {
  if (instance_ == VK_NULL_HANDLE) return;
  // The messenger is a child of the instance, so it goes first.
  if (messenger_ != VK_NULL_HANDLE) {
    auto destroy_messenger = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
    if (destroy_messenger != nullptr) destroy_messenger(instance_, messenger_, nullptr);
    messenger_ = VK_NULL_HANDLE;
  }
  vkDestroyInstance(instance_, nullptr);
  instance_ = VK_NULL_HANDLE;
}

}  // namespace odeskin::vk
