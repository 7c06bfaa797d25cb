// SPDX-License-Identifier: MIT
#include "render_pipelines.hpp"

#include <array>
#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "engine/visual/render_shading.hpp"
#include "host/vk_status.hpp"
#include "shaders/curve_colour.spv.h"
#include "shaders/curve_vertex.spv.h"
#include "shaders/surface_shade.spv.h"
#include "shaders/surface_vertex.spv.h"

namespace odeskin::vk {
namespace {

Result<UniqueShaderModule> shaderModule(VkDevice device, std::span<const std::uint32_t> spirv) {
  VkShaderModuleCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
  info.codeSize = spirv.size_bytes();
  info.pCode = spirv.data();
  VkShaderModule module = VK_NULL_HANDLE;
  ODESKIN_VK_TRY(vkCreateShaderModule(device, &info, nullptr, &module));
  return UniqueShaderModule(device, module);
}

struct PipelineDesc {
  std::span<const std::uint32_t> vertex_spirv;
  std::span<const std::uint32_t> fragment_spirv;
  std::uint32_t stride = 0;
  std::span<const VkVertexInputAttributeDescription> attributes;
  VkCompareOp depth_compare = VK_COMPARE_OP_LESS;
};

Result<UniquePipeline> createPipeline(const Device& device, VkRenderPass render_pass, VkSampleCountFlagBits samples,
                                      VkPipelineLayout layout, const PipelineDesc& desc) {
  VkDevice vk_device = device.handle();
  // Modules are only needed while the pipeline compiles.
  ODESKIN_ASSIGN_OR_RETURN(const UniqueShaderModule vertex, shaderModule(vk_device, desc.vertex_spirv));
  ODESKIN_ASSIGN_OR_RETURN(const UniqueShaderModule fragment, shaderModule(vk_device, desc.fragment_spirv));
  std::array<VkPipelineShaderStageCreateInfo, 2> stages{};
  stages[0].sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
  stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
  stages[0].module = vertex.get();
  stages[0].pName = "main";
  stages[1].sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
  stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
  stages[1].module = fragment.get();
  stages[1].pName = "main";

  // One interleaved vertex buffer at binding 0.
  VkVertexInputBindingDescription binding{0, desc.stride, VK_VERTEX_INPUT_RATE_VERTEX};
  VkPipelineVertexInputStateCreateInfo input{};
  input.sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO;
  input.vertexBindingDescriptionCount = 1;
  input.pVertexBindingDescriptions = &binding;
  input.vertexAttributeDescriptionCount = static_cast<std::uint32_t>(desc.attributes.size());
  input.pVertexAttributeDescriptions = desc.attributes.data();
  VkPipelineInputAssemblyStateCreateInfo assembly{};
  assembly.sType = VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO;
  assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;

  // Viewport and scissor are set per draw, so one pipeline serves every image size.
  VkPipelineViewportStateCreateInfo viewport{};
  viewport.sType = VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO;
  viewport.viewportCount = 1;
  viewport.scissorCount = 1;
  std::array<VkDynamicState, 2> dynamic_states{VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  VkPipelineDynamicStateCreateInfo dynamic{};
  dynamic.sType = VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO;
  dynamic.dynamicStateCount = static_cast<std::uint32_t>(dynamic_states.size());
  dynamic.pDynamicStates = dynamic_states.data();

  // No culling: open meshes (the horse's hoof hole) show their inside, lit as a front face. The
  // projection flips y, so counter-clockwise in world space stays counter-clockwise on screen.
  VkPipelineRasterizationStateCreateInfo raster{};
  raster.sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO;
  raster.polygonMode = VK_POLYGON_MODE_FILL;
  raster.cullMode = VK_CULL_MODE_NONE;
  raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
  raster.lineWidth = 1.0f;
  VkPipelineMultisampleStateCreateInfo multisample{};
  multisample.sType = VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO;
  multisample.rasterizationSamples = samples;
  VkPipelineDepthStencilStateCreateInfo depth{};
  depth.sType = VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO;
  depth.depthTestEnable = VK_TRUE;
  depth.depthWriteEnable = VK_TRUE;
  depth.depthCompareOp = desc.depth_compare;
  VkPipelineColorBlendAttachmentState blend_attachment{};
  blend_attachment.colorWriteMask =
      VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
  VkPipelineColorBlendStateCreateInfo blend{};
  blend.sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO;
  blend.attachmentCount = 1;
  blend.pAttachments = &blend_attachment;

  VkGraphicsPipelineCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO;
  info.stageCount = static_cast<std::uint32_t>(stages.size());
  info.pStages = stages.data();
  info.pVertexInputState = &input;
  info.pInputAssemblyState = &assembly;
  info.pViewportState = &viewport;
  info.pRasterizationState = &raster;
  info.pMultisampleState = &multisample;
  info.pDepthStencilState = &depth;
  info.pColorBlendState = &blend;
  info.pDynamicState = &dynamic;
  info.layout = layout;
  info.renderPass = render_pass;
  info.subpass = 0;
  VkPipeline pipeline = VK_NULL_HANDLE;
  ODESKIN_VK_TRY(vkCreateGraphicsPipelines(vk_device, device.pipelineCache(), 1, &info, nullptr, &pipeline));
  return UniquePipeline(vk_device, pipeline);
}

}  // namespace

Result<RenderPipelines> RenderPipelines::create(const Device& device, VkRenderPass render_pass,
                                                VkSampleCountFlagBits samples) {
  constexpr std::uint32_t kPushBytes = sizeof(visual::RenderPushConstants);
  if (kPushBytes > device.limits().maxPushConstantsSize) {
    return unavailable("renderer: " + std::to_string(kPushBytes) + " push constant bytes exceed maxPushConstantsSize " +
                       std::to_string(device.limits().maxPushConstantsSize));
  }
  RenderPipelines out;
  VkPushConstantRange push{kPushStages, 0, kPushBytes};
  VkPipelineLayoutCreateInfo layout_info{};
  layout_info.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
  layout_info.pushConstantRangeCount = 1;
  layout_info.pPushConstantRanges = &push;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  ODESKIN_VK_TRY(vkCreatePipelineLayout(device.handle(), &layout_info, nullptr, &layout));
  out.layout_ = UniquePipelineLayout(device.handle(), layout);

  using visual::CurveVertex;
  using visual::SurfaceVertex;
  const std::array<VkVertexInputAttributeDescription, 3> surface_attributes{{
      {ODESKIN_SURFACE_POSITION, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(SurfaceVertex, position)},
      {ODESKIN_SURFACE_NORMAL, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(SurfaceVertex, normal)},
      {ODESKIN_SURFACE_VALUE, 0, VK_FORMAT_R32_SFLOAT, offsetof(SurfaceVertex, value)},
  }};
  ODESKIN_ASSIGN_OR_RETURN(out.surface_,
                           createPipeline(device, render_pass, samples, layout,
                                          {kSurfaceVertexSpirv, kSurfaceShadeSpirv, sizeof(SurfaceVertex),
                                           surface_attributes, VK_COMPARE_OP_LESS}));
  const std::array<VkVertexInputAttributeDescription, 4> curve_attributes{{
      {ODESKIN_CURVE_POSITION, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(CurveVertex, position)},
      {ODESKIN_CURVE_OTHER, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(CurveVertex, other)},
      {ODESKIN_CURVE_SIDE, 0, VK_FORMAT_R32_SFLOAT, offsetof(CurveVertex, side)},
      {ODESKIN_CURVE_COLOUR, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(CurveVertex, colour)},
  }};
  // LESS_OR_EQUAL: a curve drawn twice over itself (a closed curve's joins) keeps its colour.
  ODESKIN_ASSIGN_OR_RETURN(out.curves_,
                           createPipeline(device, render_pass, samples, layout,
                                          {kCurveVertexSpirv, kCurveColourSpirv, sizeof(CurveVertex), curve_attributes,
                                           VK_COMPARE_OP_LESS_OR_EQUAL}));
  return out;
}

}  // namespace odeskin::vk
