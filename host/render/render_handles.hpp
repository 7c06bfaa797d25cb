// SPDX-License-Identifier: MIT
// Owners of the graphics objects the offscreen renderer adds to host/vk_handle.hpp's set.
#pragma once

#include <vulkan/vulkan.h>

#include "host/vk_handle.hpp"

namespace odeskin::vk {

using UniqueImage = DeviceHandle<VkImage, vkDestroyImage>;
using UniqueImageView = DeviceHandle<VkImageView, vkDestroyImageView>;
using UniqueRenderPass = DeviceHandle<VkRenderPass, vkDestroyRenderPass>;
using UniqueFramebuffer = DeviceHandle<VkFramebuffer, vkDestroyFramebuffer>;

}  // namespace odeskin::vk
