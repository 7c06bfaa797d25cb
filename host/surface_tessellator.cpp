// SPDX-License-Identifier: MIT
#include "surface_tessellator.hpp"

#include <algorithm>

#include "shaders/ode6_tessellate.spv.h"
#include "vk_status.hpp"

namespace odeskin {
namespace {

// Dispatches `items` invocations of `pipeline` in pieces of at most ODESKIN_TESSELLATE_MAX_GROUPS
// groups, with the descriptor set and layout of `base`.
void recordPass(VkCommandBuffer cmd, const vk::ComputePipeline& base, VkPipeline pipeline,
                gpu::TessellatePushConstants push, std::uint32_t items) {
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
  VkDescriptorSet set = base.set(0);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, base.layout(), 0, 1, &set, 0, nullptr);
  push.item_count = items;
  const std::uint32_t per_dispatch = ODESKIN_TESSELLATE_MAX_GROUPS * ODESKIN_TESSELLATE_WORKGROUP_SIZE;
  // items <= kMaxTessellationVertices (2^26), so first + per_dispatch never overflows.
  for (std::uint32_t first = 0; first < items; first += per_dispatch) {
    push.first_item = first;
    vkCmdPushConstants(cmd, base.layout(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, &push);
    const std::uint32_t count = std::min(per_dispatch, items - first);
    vkCmdDispatch(cmd, (count + ODESKIN_TESSELLATE_WORKGROUP_SIZE - 1) / ODESKIN_TESSELLATE_WORKGROUP_SIZE, 1, 1);
  }
}

// The vertex pass: the same SPIR-V with kPass = ODESKIN_TESSELLATE_PASS_POSITIONS, on `layout`.
Result<vk::UniquePipeline> vertexPipeline(const vk::Device& device, VkPipelineLayout layout) {
  VkShaderModuleCreateInfo module_info{};
  module_info.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
  module_info.codeSize = sizeof kOde6TessellateSpirv;
  module_info.pCode = kOde6TessellateSpirv;
  VkShaderModule module_handle = VK_NULL_HANDLE;
  ODESKIN_VK_TRY(vkCreateShaderModule(device.handle(), &module_info, nullptr, &module_handle));
  const vk::UniqueShaderModule shader_module(device.handle(), module_handle);
  const std::uint32_t pass = ODESKIN_TESSELLATE_PASS_POSITIONS;
  const VkSpecializationMapEntry entry{ODESKIN_TESSELLATE_PASS_CONSTANT_ID, 0, sizeof pass};
  VkSpecializationInfo specialization{};
  specialization.mapEntryCount = 1;
  specialization.pMapEntries = &entry;
  specialization.dataSize = sizeof pass;
  specialization.pData = &pass;
  VkComputePipelineCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO;
  info.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
  info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  info.stage.module = module_handle;
  info.stage.pName = "main";
  info.stage.pSpecializationInfo = &specialization;
  info.layout = layout;
  VkPipeline pipeline = VK_NULL_HANDLE;
  ODESKIN_VK_TRY(vkCreateComputePipelines(device.handle(), device.pipelineCache(), 1, &info, nullptr, &pipeline));
  return vk::UniquePipeline(device.handle(), pipeline);
}

}  // namespace

Result<SurfaceTessellator> SurfaceTessellator::create(const vk::Device& device, const Network& network,
                                                      TessellationResolution resolution) {
  SurfaceTessellator t;
  t.device_ = &device;
  ODESKIN_ASSIGN_OR_RETURN(t.data_, packTessellation(network, resolution));
  ODESKIN_ASSIGN_OR_RETURN(t.cardinals_, vk::createStorageBuffer(device, std::as_bytes(std::span(t.data_.cardinals))));
  ODESKIN_ASSIGN_OR_RETURN(t.patch_cardinals_,
                           vk::createStorageBuffer(device, std::as_bytes(std::span(t.data_.patch_cardinals))));
  ODESKIN_ASSIGN_OR_RETURN(t.boundary_samples_,
                           vk::createStorageBuffer(device, std::as_bytes(std::span(t.data_.boundary_samples))));
  const VkDeviceSize table_bytes = std::max<VkDeviceSize>(16, t.data_.tableFloats() * sizeof(float));
  const VkDeviceSize position_bytes = std::max<VkDeviceSize>(16, t.data_.grid.vertexCount() * sizeof(gpu::Float4));
  for (VkDeviceSize bytes : {table_bytes, position_bytes}) {
    if (bytes > device.limits().maxStorageBufferRange) {
      return unavailable("surface tessellation: " + std::to_string(bytes) + " bytes exceed maxStorageBufferRange (" +
                         std::to_string(device.limits().maxStorageBufferRange) + ") of " + device.name());
    }
  }
  ODESKIN_ASSIGN_OR_RETURN(t.table_, vk::Buffer::create(device, table_bytes, vk::kOutputBufferUsage));
  ODESKIN_ASSIGN_OR_RETURN(t.positions_, vk::Buffer::create(device, position_bytes, vk::kOutputBufferUsage));
  ODESKIN_ASSIGN_OR_RETURN(t.timestamps_, vk::TimestampQueries::create(device, 1));

  const std::uint32_t bindings[] = {ODESKIN_TESSELLATE_BINDING_CARDINALS, ODESKIN_TESSELLATE_BINDING_PATCH_CARDINALS,
                                    ODESKIN_TESSELLATE_BINDING_BOUNDARY_SAMPLES, ODESKIN_TESSELLATE_BINDING_TABLE,
                                    ODESKIN_TESSELLATE_BINDING_OUT_POSITIONS};
  vk::ComputePipelineDesc desc;
  desc.spirv = kOde6TessellateSpirv;
  desc.storage_bindings = bindings;
  desc.push_constant_bytes = sizeof(gpu::TessellatePushConstants);
  desc.descriptor_set_count = 1;
  ODESKIN_ASSIGN_OR_RETURN(t.pipeline_, vk::ComputePipeline::create(device, desc));
  ODESKIN_TRY(t.pipeline_.bindBuffer(0, ODESKIN_TESSELLATE_BINDING_CARDINALS, t.cardinals_.handle()));
  ODESKIN_TRY(t.pipeline_.bindBuffer(0, ODESKIN_TESSELLATE_BINDING_PATCH_CARDINALS, t.patch_cardinals_.handle()));
  ODESKIN_TRY(t.pipeline_.bindBuffer(0, ODESKIN_TESSELLATE_BINDING_BOUNDARY_SAMPLES, t.boundary_samples_.handle()));
  ODESKIN_TRY(t.pipeline_.bindBuffer(0, ODESKIN_TESSELLATE_BINDING_TABLE, t.table_.handle()));
  ODESKIN_TRY(t.pipeline_.bindBuffer(0, ODESKIN_TESSELLATE_BINDING_OUT_POSITIONS, t.positions_.handle()));
  ODESKIN_ASSIGN_OR_RETURN(t.vertex_pipeline_, vertexPipeline(device, t.pipeline_.layout()));
  return t;
}

Status SurfaceTessellator::run() {
  const auto table_items = static_cast<std::uint32_t>(data_.cardinals.size() * data_.grid.u_samples);
  const auto vertices = static_cast<std::uint32_t>(data_.grid.vertexCount());
  ODESKIN_TRY(device_->submitAndWait([&](VkCommandBuffer cmd) {
    timestamps_.recordBegin(cmd, 0);
    recordPass(cmd, pipeline_, pipeline_.pipeline(), data_.push, table_items);
    // The vertex pass reads the table the first pass wrote.
    vk::recordMemoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                            VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
    recordPass(cmd, pipeline_, vertex_pipeline_.get(), data_.push, vertices);
    // Results are read back by transfers (staged downloads) or mapped memory.
    vk::recordMemoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                            VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_HOST_BIT,
                            VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_HOST_READ_BIT);
    timestamps_.recordEnd(cmd, 0);
  }));
  ODESKIN_ASSIGN_OR_RETURN(last_gpu_seconds_, timestamps_.seconds(0));
  return okStatus();
}

Status SurfaceTessellator::readPositions(std::span<gpu::Float4> out) const {
  if (out.size() != data_.grid.vertexCount()) {
    return invalidArgument("surface tessellation: out has " + std::to_string(out.size()) + " entries, expected " +
                           std::to_string(data_.grid.vertexCount()));
  }
  return vk::downloadSpan(*device_, positions_, out);
}

Status SurfaceTessellator::readCardinalTable(std::span<float> out) const {
  if (out.size() != data_.tableFloats()) {
    return invalidArgument("surface tessellation: out has " + std::to_string(out.size()) + " entries, expected " +
                           std::to_string(data_.tableFloats()));
  }
  return vk::downloadSpan(*device_, table_, out);
}

}  // namespace odeskin
