// SPDX-License-Identifier: MIT
// Where the offscreen renderer draws: a multisampled RGBA8 colour image and a depth image, a
// single-sample image they resolve into, one render pass and framebuffer over them, and a
// host-visible buffer the resolved image is copied to so the CPU can read the pixels.
#pragma once

#include <cstdint>

#include <vulkan/vulkan.h>

#include "engine/core/result.hpp"
#include "engine/visual/image.hpp"
#include "host/buffer.hpp"
#include "host/device.hpp"
#include "render_handles.hpp"

namespace odeskin::vk {

// The colour format: linear UNORM, so a shader's colour x is stored as round(255 x), exactly what
// the CPU reference (visual::toRgba8) predicts. No sRGB encoding happens anywhere.
inline constexpr VkFormat kRenderColourFormat = VK_FORMAT_R8G8B8A8_UNORM;

// An image with its own memory and a view of its single mip level and layer.
struct AttachmentImage {
  UniqueMemory memory;  // declared first: destroyed last
  UniqueImage image;
  UniqueImageView view;
};

class RenderTarget {
 public:
  // width x height pixels with `samples` samples per pixel (a count the device supports for colour
  // and depth, see chooseSampleCount). kInvalidArgument: zero size, or above the device's image or
  // framebuffer limits (both named); kUnavailable: no usable depth format, or RGBA8 cannot be a
  // colour attachment or copied from.
  static Result<RenderTarget> create(const Device& device, std::uint32_t width, std::uint32_t height,
                                     VkSampleCountFlagBits samples);

  RenderTarget() = default;
  RenderTarget(RenderTarget&&) noexcept = default;
  RenderTarget& operator=(RenderTarget&&) noexcept = default;

  std::uint32_t width() const { return width_; }
  std::uint32_t height() const { return height_; }
  VkSampleCountFlagBits samples() const { return samples_; }
  VkRenderPass renderPass() const { return render_pass_.get(); }
  VkFramebuffer framebuffer() const { return framebuffer_.get(); }

  // Records, after the render pass has ended, the copy of the resolved image into the readback
  // buffer and the barrier that makes it visible to the host.
  void recordReadback(VkCommandBuffer cmd) const;
  // The pixels of the last readback (the caller has waited for it).
  visual::Image pixels() const;

 private:
  std::uint32_t width_ = 0;
  std::uint32_t height_ = 0;
  VkSampleCountFlagBits samples_ = VK_SAMPLE_COUNT_1_BIT;
  // Destroyed bottom-up: buffer, framebuffer, then the images it points at, then the pass.
  UniqueRenderPass render_pass_;
  AttachmentImage colour_;   // multisampled when samples > 1, else the image that is read back
  AttachmentImage depth_;
  AttachmentImage resolve_;  // samples > 1 only
  UniqueFramebuffer framebuffer_;
  Buffer readback_;
};

// The largest sample count <= `requested` (rounded down to a power of two, at least 1) that the
// device supports for both colour and depth framebuffer attachments.
VkSampleCountFlagBits chooseSampleCount(const Device& device, std::uint32_t requested);

}  // namespace odeskin::vk
