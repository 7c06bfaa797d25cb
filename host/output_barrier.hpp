// SPDX-License-Identifier: MIT
// The barrier a renderer records before reading a deformer's output buffer as vertex input (same
// queue, a later submission): compute-shader writes made visible to vertex attribute fetch.
#pragma once

#include <vulkan/vulkan.h>

namespace odeskin {

struct OutputBarrier {
  VkPipelineStageFlags src_stage = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;
  VkPipelineStageFlags dst_stage = VK_PIPELINE_STAGE_VERTEX_INPUT_BIT;
  VkBufferMemoryBarrier barrier{};
};

// SHADER_WRITE -> VERTEX_ATTRIBUTE_READ on [offset, offset + size) of `buffer`.
inline VkBufferMemoryBarrier vertexInputBarrier(VkBuffer buffer, VkDeviceSize offset = 0,
                                                VkDeviceSize size = VK_WHOLE_SIZE) {
  VkBufferMemoryBarrier b{};
  b.sType = VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER;
  b.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
  b.dstAccessMask = VK_ACCESS_VERTEX_ATTRIBUTE_READ_BIT;
  b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.buffer = buffer;
  b.offset = offset;
  b.size = size;
  return b;
}

}  // namespace odeskin
