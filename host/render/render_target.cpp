// SPDX-License-Identifier: MIT
#include "render_target.hpp"

#include <array>
#include <cstring>
#include <string>
#include <vector>

#include "host/fault_injection.hpp"
#include "host/vk_status.hpp"

namespace odeskin::vk {
namespace {

bool hasFeatures(const Device& device, VkFormat format, VkFormatFeatureFlags features) {
  VkFormatProperties properties;
  vkGetPhysicalDeviceFormatProperties(device.physicalDevice(), format, &properties);
  return (properties.optimalTilingFeatures & features) == features;
}

// The spec guarantees D16 and one of X8_D24 / D32_SFLOAT; the most precise one wins.
Result<VkFormat> depthFormat(const Device& device) {
  for (VkFormat format : {VK_FORMAT_D32_SFLOAT, VK_FORMAT_X8_D24_UNORM_PACK32, VK_FORMAT_D16_UNORM}) {
    if (hasFeatures(device, format, VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT)) return format;
  }
  return unavailable(std::string("no depth attachment format on ") + device.name());
}

Result<AttachmentImage> createAttachment(const Device& device, std::uint32_t width, std::uint32_t height,
                                         VkFormat format, VkImageUsageFlags usage, VkSampleCountFlagBits samples,
                                         VkImageAspectFlags aspect) {
  VkDevice vk_device = device.handle();
  AttachmentImage out;
  VkImageCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO;
  info.imageType = VK_IMAGE_TYPE_2D;
  info.format = format;
  info.extent = {width, height, 1};
  info.mipLevels = 1;
  info.arrayLayers = 1;
  info.samples = samples;
  info.tiling = VK_IMAGE_TILING_OPTIMAL;
  info.usage = usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  VkImage image = VK_NULL_HANDLE;
  ODESKIN_VK_TRY(vkCreateImage(vk_device, &info, nullptr, &image));
  out.image = UniqueImage(vk_device, image);

  // Device-local when there is such a type; any type the image accepts otherwise.
  VkMemoryRequirements requirements;
  vkGetImageMemoryRequirements(vk_device, image, &requirements);
  ODESKIN_ASSIGN_OR_RETURN(const std::uint32_t type,
                           device.findMemoryType(requirements.memoryTypeBits, 0, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT));
  VkMemoryAllocateInfo alloc{};
  alloc.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
  alloc.allocationSize = requirements.size;
  alloc.memoryTypeIndex = type;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkResult allocated = injectedResult(VkFault::kOutOfMemory);
  if (allocated == VK_SUCCESS) allocated = vkAllocateMemory(vk_device, &alloc, nullptr, &memory);
  ODESKIN_TRY(vkStatus(allocated, "vkAllocateMemory"));
  out.memory = UniqueMemory(vk_device, memory);
  ODESKIN_VK_TRY(vkBindImageMemory(vk_device, image, memory, 0));

  VkImageViewCreateInfo view_info{};
  view_info.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO;
  view_info.image = image;
  view_info.viewType = VK_IMAGE_VIEW_TYPE_2D;
  view_info.format = format;
  view_info.subresourceRange = {aspect, 0, 1, 0, 1};
  VkImageView view = VK_NULL_HANDLE;
  ODESKIN_VK_TRY(vkCreateImageView(vk_device, &view_info, nullptr, &view));
  out.view = UniqueImageView(vk_device, view);
  return out;
}

// One subpass: colour (resolved into attachment 2 when multisampled) and depth. The pass ends with
// the read-back image in TRANSFER_SRC_OPTIMAL, ready for the copy recordReadback() adds.
Result<UniqueRenderPass> createRenderPass(VkDevice device, VkFormat depth_format, VkSampleCountFlagBits samples) {
  const bool resolve = samples != VK_SAMPLE_COUNT_1_BIT;
  std::vector<VkAttachmentDescription> attachments(resolve ? 3 : 2);
  VkAttachmentDescription& colour = attachments[0];
  colour.format = kRenderColourFormat;
  colour.samples = samples;
  colour.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  colour.storeOp = resolve ? VK_ATTACHMENT_STORE_OP_DONT_CARE : VK_ATTACHMENT_STORE_OP_STORE;
  colour.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  colour.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  colour.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  colour.finalLayout = resolve ? VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL : VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
  VkAttachmentDescription& depth = attachments[1];
  depth.format = depth_format;
  depth.samples = samples;
  depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  depth.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  depth.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  depth.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  depth.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  depth.finalLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
  if (resolve) {
    VkAttachmentDescription& target = attachments[2];
    target.format = kRenderColourFormat;
    target.samples = VK_SAMPLE_COUNT_1_BIT;
    target.loadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    target.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    target.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    target.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    target.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    target.finalLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
  }
  VkAttachmentReference colour_ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  VkAttachmentReference depth_ref{1, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
  VkAttachmentReference resolve_ref{2, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = 1;
  subpass.pColorAttachments = &colour_ref;
  subpass.pResolveAttachments = resolve ? &resolve_ref : nullptr;
  subpass.pDepthStencilAttachment = &depth_ref;

  // Before: the previous picture's copy out of the image, and its colour and depth writes, must
  // finish before this one writes them (render() also waits on its fence; the pass does not rely on it).
  // After: colour writes and the resolve must land before the copy to the readback buffer.
  std::array<VkSubpassDependency, 2> dependencies{};
  dependencies[0].srcSubpass = VK_SUBPASS_EXTERNAL;
  dependencies[0].dstSubpass = 0;
  dependencies[0].srcStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT |
                                 VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
  dependencies[0].dstStageMask =
      VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT;
  dependencies[0].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
  dependencies[0].dstAccessMask =
      VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
  dependencies[1].srcSubpass = 0;
  dependencies[1].dstSubpass = VK_SUBPASS_EXTERNAL;
  dependencies[1].srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  dependencies[1].dstStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
  dependencies[1].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  dependencies[1].dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;

  VkRenderPassCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO;
  info.attachmentCount = static_cast<std::uint32_t>(attachments.size());
  info.pAttachments = attachments.data();
  info.subpassCount = 1;
  info.pSubpasses = &subpass;
  info.dependencyCount = static_cast<std::uint32_t>(dependencies.size());
  info.pDependencies = dependencies.data();
  VkRenderPass pass = VK_NULL_HANDLE;
  ODESKIN_VK_TRY(vkCreateRenderPass(device, &info, nullptr, &pass));
  return UniqueRenderPass(device, pass);
}

}  // namespace

VkSampleCountFlagBits chooseSampleCount(const Device& device, std::uint32_t requested) {
  const VkSampleCountFlags supported =
      device.limits().framebufferColorSampleCounts & device.limits().framebufferDepthSampleCounts;
  for (std::uint32_t count = 64; count > 1; count /= 2) {
    if (count <= requested && (supported & count)) return static_cast<VkSampleCountFlagBits>(count);
  }
  return VK_SAMPLE_COUNT_1_BIT;
}

Result<RenderTarget> RenderTarget::create(const Device& device, std::uint32_t width, std::uint32_t height,
                                          VkSampleCountFlagBits samples) {
  const VkPhysicalDeviceLimits& limits = device.limits();
  if (width == 0 || height == 0) return invalidArgument("render target: the image size must be at least 1 x 1");
  const std::uint32_t max_w = std::min(limits.maxImageDimension2D, limits.maxFramebufferWidth);
  const std::uint32_t max_h = std::min(limits.maxImageDimension2D, limits.maxFramebufferHeight);
  if (width > max_w || height > max_h) {
    return invalidArgument("render target: " + std::to_string(width) + " x " + std::to_string(height) +
                           " exceeds the device's largest framebuffer, " + std::to_string(max_w) + " x " +
                           std::to_string(max_h));
  }
  if (!hasFeatures(device, kRenderColourFormat,
                   VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT | VK_FORMAT_FEATURE_TRANSFER_SRC_BIT)) {
    return unavailable(std::string("RGBA8 cannot be a colour attachment and copy source on ") + device.name());
  }
  ODESKIN_ASSIGN_OR_RETURN(const VkFormat depth_format, depthFormat(device));

  RenderTarget target;
  target.width_ = width;
  target.height_ = height;
  target.samples_ = samples;
  const bool resolve = samples != VK_SAMPLE_COUNT_1_BIT;
  ODESKIN_ASSIGN_OR_RETURN(target.render_pass_, createRenderPass(device.handle(), depth_format, samples));

  // Multisampled images are never read after the pass: transient lets a tiler keep them on chip.
  const VkImageUsageFlags colour_usage =
      VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT |
      (resolve ? VK_IMAGE_USAGE_TRANSIENT_ATTACHMENT_BIT : VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
  ODESKIN_ASSIGN_OR_RETURN(target.colour_, createAttachment(device, width, height, kRenderColourFormat, colour_usage,
                                                            samples, VK_IMAGE_ASPECT_COLOR_BIT));
  ODESKIN_ASSIGN_OR_RETURN(target.depth_,
                           createAttachment(device, width, height, depth_format,
                                            VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT |
                                                VK_IMAGE_USAGE_TRANSIENT_ATTACHMENT_BIT,
                                            samples, VK_IMAGE_ASPECT_DEPTH_BIT));
  if (resolve) {
    ODESKIN_ASSIGN_OR_RETURN(target.resolve_,
                             createAttachment(device, width, height, kRenderColourFormat,
                                              VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                                              VK_SAMPLE_COUNT_1_BIT, VK_IMAGE_ASPECT_COLOR_BIT));
  }

  std::vector<VkImageView> views{target.colour_.view.get(), target.depth_.view.get()};
  if (resolve) views.push_back(target.resolve_.view.get());
  VkFramebufferCreateInfo fb{};
  fb.sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO;
  fb.renderPass = target.render_pass_.get();
  fb.attachmentCount = static_cast<std::uint32_t>(views.size());
  fb.pAttachments = views.data();
  fb.width = width;
  fb.height = height;
  fb.layers = 1;
  VkFramebuffer framebuffer = VK_NULL_HANDLE;
  ODESKIN_VK_TRY(vkCreateFramebuffer(device.handle(), &fb, nullptr, &framebuffer));
  target.framebuffer_ = UniqueFramebuffer(device.handle(), framebuffer);

  ODESKIN_ASSIGN_OR_RETURN(target.readback_, Buffer::create(device, VkDeviceSize(width) * height * 4,
                                                            VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::kHostReadback));
  return target;
}

void RenderTarget::recordReadback(VkCommandBuffer cmd) const {
  VkImage source = samples_ != VK_SAMPLE_COUNT_1_BIT ? resolve_.image.get() : colour_.image.get();
  VkBufferImageCopy region{};
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.imageExtent = {width_, height_, 1};
  vkCmdCopyImageToBuffer(cmd, source, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback_.handle(), 1, &region);
  VkBufferMemoryBarrier barrier{};
  barrier.sType = VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER;
  barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.buffer = readback_.handle();
  barrier.size = VK_WHOLE_SIZE;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 0, nullptr, 1, &barrier, 0,
                       nullptr);
}

visual::Image RenderTarget::pixels() const {
  visual::Image image(width_, height_);
  std::memcpy(image.pixels.data(), readback_.mapped(), image.pixels.size() * sizeof(visual::Rgba8));
  return image;
}

}  // namespace odeskin::vk
