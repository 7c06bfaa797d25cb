// SPDX-License-Identifier: MIT
#include "compute_pipeline.hpp"

#include <algorithm>
#include <string>

#include "vk_status.hpp"

namespace odeskin::vk {
namespace {

// Bytes per texel of the 32-bit formats the shaders fetch; 0 for any other format.
VkDeviceSize texelBytes(VkFormat format) {
  switch (format) {
    case VK_FORMAT_R32_UINT:
    case VK_FORMAT_R32_SFLOAT:
      return 4;
    case VK_FORMAT_R32G32_UINT:
    case VK_FORMAT_R32G32_SFLOAT:
      return 8;
    case VK_FORMAT_R32G32B32A32_UINT:
    case VK_FORMAT_R32G32B32A32_SFLOAT:
      return 16;
    default:
      return 0;
  }
}

}  // namespace

Result<ComputePipeline> ComputePipeline::create(const Device& device, const ComputePipelineDesc& desc) {
  if (desc.spirv.empty()) return invalidArgument("ComputePipeline: spirv is empty");
  if (desc.descriptor_set_count == 0) return invalidArgument("ComputePipeline: descriptor_set_count is 0");
  if (desc.push_constant_bytes % 4 != 0) {
    return invalidArgument("ComputePipeline: push_constant_bytes must be a multiple of 4");
  }
  if (desc.push_constant_bytes > device.limits().maxPushConstantsSize) {
    return unavailable("ComputePipeline: " + std::to_string(desc.push_constant_bytes) +
                       " push constant bytes exceed maxPushConstantsSize " +
                       std::to_string(device.limits().maxPushConstantsSize));
  }
  VkDevice vk_device = device.handle();
  ComputePipeline result;
  result.device_ = vk_device;
  result.push_constant_bytes_ = desc.push_constant_bytes;
  result.max_texel_elements_ = device.limits().maxTexelBufferElements;
  result.texel_bindings_.assign(desc.texel_bindings.begin(), desc.texel_bindings.end());

  // Set 0: one descriptor per binding the shader declares, all read in the compute stage.
  std::vector<VkDescriptorSetLayoutBinding> bindings;
  auto add = [&bindings](std::uint32_t binding, VkDescriptorType type) {
    VkDescriptorSetLayoutBinding b{};
    b.binding = binding;
    b.descriptorType = type;
    b.descriptorCount = 1;
    b.stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
    bindings.push_back(b);
  };
  for (std::uint32_t binding : desc.storage_bindings) add(binding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  for (const TexelBinding& t : desc.texel_bindings) {
    if (texelBytes(t.format) == 0) {
      return invalidArgument("ComputePipeline: binding " + std::to_string(t.binding) + " has a texel format other than 32-bit R, RG or RGBA");
    }
    if (std::find(desc.storage_bindings.begin(), desc.storage_bindings.end(), t.binding) != desc.storage_bindings.end()) {
      return invalidArgument("ComputePipeline: binding " + std::to_string(t.binding) + " is both a storage and a texel buffer");
    }
    add(t.binding, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER);
  }
  VkDescriptorSetLayoutCreateInfo set_info{};
  set_info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
  set_info.bindingCount = static_cast<std::uint32_t>(bindings.size());
  set_info.pBindings = bindings.data();
  VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
  ODESKIN_VK_TRY(vkCreateDescriptorSetLayout(vk_device, &set_info, nullptr, &set_layout));
  result.set_layout_ = UniqueDescriptorSetLayout(vk_device, set_layout);

  // Per-dispatch scalars travel as push constants: no buffer update between frames.
  VkPushConstantRange push{};
  push.stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
  push.size = desc.push_constant_bytes;
  VkPipelineLayoutCreateInfo layout_info{};
  layout_info.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
  layout_info.setLayoutCount = 1;
  layout_info.pSetLayouts = &set_layout;
  layout_info.pushConstantRangeCount = desc.push_constant_bytes > 0 ? 1 : 0;
  layout_info.pPushConstantRanges = &push;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  ODESKIN_VK_TRY(vkCreatePipelineLayout(vk_device, &layout_info, nullptr, &layout));
  result.layout_ = UniquePipelineLayout(vk_device, layout);

  // The shader module is only needed while the pipeline is compiled; it dies at scope exit.
  VkShaderModuleCreateInfo module_info{};
  module_info.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
  module_info.codeSize = desc.spirv.size_bytes();
  module_info.pCode = desc.spirv.data();
  VkShaderModule module_handle = VK_NULL_HANDLE;
  ODESKIN_VK_TRY(vkCreateShaderModule(vk_device, &module_info, nullptr, &module_handle));
  UniqueShaderModule shader_module(vk_device, module_handle);

  // Workgroup size is fixed in the shader (ODESKIN_WORKGROUP_SIZE), so no specialization constants.
  VkComputePipelineCreateInfo pipeline_info{};
  pipeline_info.sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO;
  pipeline_info.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
  pipeline_info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  pipeline_info.stage.module = module_handle;
  pipeline_info.stage.pName = "main";
  pipeline_info.layout = layout;
  VkPipeline pipeline = VK_NULL_HANDLE;
  ODESKIN_VK_TRY(vkCreateComputePipelines(vk_device, device.pipelineCache(), 1, &pipeline_info, nullptr, &pipeline));
  result.pipeline_ = UniquePipeline(vk_device, pipeline);

  // Exactly enough descriptors for `descriptor_set_count` sets; sets are freed with the pool.
  std::vector<VkDescriptorPoolSize> pool_sizes;
  const auto storage_count = static_cast<std::uint32_t>(desc.storage_bindings.size());
  const auto texel_count = static_cast<std::uint32_t>(desc.texel_bindings.size());
  if (storage_count > 0) {
    pool_sizes.push_back({VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, storage_count * desc.descriptor_set_count});
  }
  if (texel_count > 0) {
    pool_sizes.push_back({VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, texel_count * desc.descriptor_set_count});
  }
  VkDescriptorPoolCreateInfo pool_info{};
  pool_info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
  pool_info.maxSets = desc.descriptor_set_count;
  pool_info.poolSizeCount = static_cast<std::uint32_t>(pool_sizes.size());
  pool_info.pPoolSizes = pool_sizes.data();
  VkDescriptorPool pool = VK_NULL_HANDLE;
  ODESKIN_VK_TRY(vkCreateDescriptorPool(vk_device, &pool_info, nullptr, &pool));
  result.pool_ = UniqueDescriptorPool(vk_device, pool);

  std::vector<VkDescriptorSetLayout> layouts(desc.descriptor_set_count, set_layout);
  VkDescriptorSetAllocateInfo alloc{};
  alloc.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
  alloc.descriptorPool = pool;
  alloc.descriptorSetCount = desc.descriptor_set_count;
  alloc.pSetLayouts = layouts.data();
  result.sets_.resize(desc.descriptor_set_count);
  ODESKIN_VK_TRY(vkAllocateDescriptorSets(vk_device, &alloc, result.sets_.data()));
  result.views_.resize(std::size_t{desc.descriptor_set_count} * texel_count);
  return result;
}

Status ComputePipeline::bindBuffer(std::uint32_t set_index, std::uint32_t binding, VkBuffer buffer,
                                   VkDeviceSize offset, VkDeviceSize range) {
  VkWriteDescriptorSet write{};
  write.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
  write.dstSet = sets_[set_index];
  write.dstBinding = binding;
  write.descriptorCount = 1;
  const auto texel = std::find_if(texel_bindings_.begin(), texel_bindings_.end(),
                                  [binding](const TexelBinding& t) { return t.binding == binding; });
  if (texel == texel_bindings_.end()) {
    const VkDescriptorBufferInfo info{buffer, offset, range};
    write.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    write.pBufferInfo = &info;
    vkUpdateDescriptorSets(device_, 1, &write, 0, nullptr);
    return okStatus();
  }
  if (range != VK_WHOLE_SIZE) {
    const VkDeviceSize texel_bytes = texelBytes(texel->format);
    if (texel_bytes == 0) {  // create() refuses other formats, so this is a broken invariant
      return internalError("ComputePipeline: binding " + std::to_string(binding) + " has no texel size");
    }
    if (range / texel_bytes > max_texel_elements_) {
      return unavailable("ComputePipeline: binding " + std::to_string(binding) + " holds " +
                         std::to_string(range / texel_bytes) + " texels, more than maxTexelBufferElements (" +
                         std::to_string(max_texel_elements_) + ")");
    }
  }
  VkBufferViewCreateInfo view_info{};
  view_info.sType = VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO;
  view_info.buffer = buffer;
  view_info.format = texel->format;
  view_info.offset = offset;
  view_info.range = range;
  VkBufferView view = VK_NULL_HANDLE;
  ODESKIN_VK_TRY(vkCreateBufferView(device_, &view_info, nullptr, &view));
  const auto k = static_cast<std::size_t>(texel - texel_bindings_.begin());
  // The set's old view (if any) goes only after the descriptor stops naming it.
  UniqueBufferView replaced = std::move(views_[set_index * texel_bindings_.size() + k]);
  views_[set_index * texel_bindings_.size() + k] = UniqueBufferView(device_, view);
  write.descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
  write.pTexelBufferView = &view;
  vkUpdateDescriptorSets(device_, 1, &write, 0, nullptr);
  return okStatus();
}

void ComputePipeline::recordDispatch(VkCommandBuffer cmd, std::uint32_t set_index, const void* push,
                                     std::uint32_t group_count_x) const {
  if (group_count_x == 0) return;
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_.get());
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_.get(), 0, 1, &sets_[set_index], 0, nullptr);
  if (push_constant_bytes_ > 0) {
    vkCmdPushConstants(cmd, layout_.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, push_constant_bytes_, push);
  }
  vkCmdDispatch(cmd, group_count_x, 1, 1);
}

void recordMemoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags src_stage, VkAccessFlags src_access,
                         VkPipelineStageFlags dst_stage, VkAccessFlags dst_access) {
  VkMemoryBarrier barrier{};
  barrier.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
  barrier.srcAccessMask = src_access;
  barrier.dstAccessMask = dst_access;
  vkCmdPipelineBarrier(cmd, src_stage, dst_stage, 0, 1, &barrier, 0, nullptr, 0, nullptr);
}

}  // namespace odeskin::vk
