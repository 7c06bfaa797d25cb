// SPDX-License-Identifier: MIT
// The two graphics pipelines of the offscreen renderer, built from embedded SPIR-V: surfaces
// (surface_vertex.vert + surface_shade.frag, triangles, depth-tested, both faces drawn) and curves
// (curve_vertex.vert + curve_colour.frag, screen-space quads). One pipeline layout: the
// RenderPushConstants block (render_shading.h), seen by both stages; no descriptor sets.
#pragma once

#include <vulkan/vulkan.h>

#include "engine/core/result.hpp"
#include "host/device.hpp"
#include "host/vk_handle.hpp"

namespace odeskin::vk {

class RenderPipelines {
 public:
  // For subpass 0 of `render_pass` with `samples` samples per pixel. kUnavailable when the push
  // block exceeds maxPushConstantsSize; kDeviceError from the driver.
  static Result<RenderPipelines> create(const Device& device, VkRenderPass render_pass, VkSampleCountFlagBits samples);

  RenderPipelines() = default;
  RenderPipelines(RenderPipelines&&) noexcept = default;
  RenderPipelines& operator=(RenderPipelines&&) noexcept = default;

  VkPipelineLayout layout() const { return layout_.get(); }
  VkPipeline surface() const { return surface_.get(); }
  VkPipeline curves() const { return curves_.get(); }
  // Stages that read the push block (for vkCmdPushConstants).
  static constexpr VkShaderStageFlags kPushStages = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;

 private:
  UniquePipelineLayout layout_;  // destroyed after the pipelines that use it
  UniquePipeline surface_;
  UniquePipeline curves_;
};

}  // namespace odeskin::vk
