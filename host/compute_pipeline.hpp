// SPDX-License-Identifier: MIT
// A compute pipeline built from embedded SPIR-V whose descriptor set 0 holds storage buffers and
// uniform texel buffers, with a push constant block and a small pool of descriptor sets (one per
// frame in flight).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <vulkan/vulkan.h>

#include "device.hpp"
#include "engine/core/result.hpp"
#include "vk_handle.hpp"

namespace odeskin::vk {

// A read-only input the shader declares as a (u)samplerBuffer and reads with texelFetch. Lavapipe
// runs every storage-buffer load lane by lane, component by component, with a branch each, but
// fetches a texel's components with one gather (docs/performance.md, "Lavapipe"); GPUs read both
// through their caches alike.
struct TexelBinding {
  std::uint32_t binding = 0;
  VkFormat format = VK_FORMAT_UNDEFINED;  // one texel: the element the shader fetches
};

struct ComputePipelineDesc {
  std::span<const std::uint32_t> spirv;             // required: SPIR-V words, entry point "main"
  std::span<const std::uint32_t> storage_bindings;  // storage-buffer binding numbers of set 0
  std::span<const TexelBinding> texel_bindings;     // uniform texel buffers of set 0 (none in both lists)
  std::uint32_t push_constant_bytes = 0;            // <= limits.maxPushConstantsSize, multiple of 4
  std::uint32_t descriptor_set_count = 1;           // >= 1
};

class ComputePipeline {
 public:
  // kInvalidArgument for empty SPIR-V, zero sets or a push block not a multiple of 4;
  // kUnavailable when the push block exceeds the device limit; kDeviceError from the driver.
  static Result<ComputePipeline> create(const Device& device, const ComputePipelineDesc& desc);

  ComputePipeline() = default;
  ComputePipeline(ComputePipeline&&) noexcept = default;
  ComputePipeline& operator=(ComputePipeline&&) noexcept = default;

  VkPipeline pipeline() const { return pipeline_.get(); }
  VkPipelineLayout layout() const { return layout_.get(); }
  VkDescriptorSet set(std::uint32_t index) const { return sets_[index]; }
  std::uint32_t setCount() const { return static_cast<std::uint32_t>(sets_.size()); }

  // Points `binding` of descriptor set `set_index` at [offset, offset + range) of `buffer`, through a
  // new buffer view for a texel binding (the buffer needs UNIFORM_TEXEL_BUFFER usage, `offset` the
  // device's texel alignment). Only while no submitted work uses that set. kUnavailable when the
  // range holds more texels than maxTexelBufferElements; kDeviceError from the driver.
  Status bindBuffer(std::uint32_t set_index, std::uint32_t binding, VkBuffer buffer, VkDeviceSize offset = 0,
                    VkDeviceSize range = VK_WHOLE_SIZE);
  // Binds the pipeline, set `set_index` and `push` (push_constant_bytes long), then dispatches
  // `group_count_x` workgroups (nothing when 0).
  void recordDispatch(VkCommandBuffer cmd, std::uint32_t set_index, const void* push,
                      std::uint32_t group_count_x) const;

 private:
  VkDevice device_ = VK_NULL_HANDLE;
  std::uint32_t push_constant_bytes_ = 0;
  std::uint32_t max_texel_elements_ = 0;
  std::vector<TexelBinding> texel_bindings_;
  // Destroyed bottom-up: pool (frees the sets) and pipeline before the layouts they use.
  UniqueDescriptorSetLayout set_layout_;
  UniquePipelineLayout layout_;
  UniquePipeline pipeline_;
  UniqueDescriptorPool pool_;
  std::vector<VkDescriptorSet> sets_;
  // views_[set * texel_bindings_.size() + k]: what texel binding k of that set points at.
  std::vector<UniqueBufferView> views_;
};

// One global memory barrier: `src_access` writes of `src_stage` made visible to `dst_access` of
// `dst_stage` (no image or buffer ranges: every pass here reads or writes whole buffers).
void recordMemoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags src_stage, VkAccessFlags src_access,
                         VkPipelineStageFlags dst_stage, VkAccessFlags dst_access);

}  // namespace odeskin::vk
