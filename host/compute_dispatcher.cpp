// SPDX-License-Identifier: MIT
#include "compute_dispatcher.hpp"

#include "texel_bindings.hpp"

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

namespace odeskin::vk {

VkPipelineStageFlags outputReuseStages(const Device& device) {
  VkPipelineStageFlags stages = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT;
  // A renderer on a graphics queue may fetch the output as vertices; that stage only exists there.
  if (device.queueFlags() & VK_QUEUE_GRAPHICS_BIT) stages |= VK_PIPELINE_STAGE_VERTEX_INPUT_BIT;
  return stages;
}

Result<ComputeDispatcher> ComputeDispatcher::create(const Device& device, const ComputeDispatcherDesc& desc) {
  if (desc.frames_in_flight == 0) return invalidArgument("ComputeDispatcher: frames_in_flight is 0");
  ComputeDispatcher d;
  d.reuse_stages_ = outputReuseStages(device);

  std::vector<std::uint32_t> bindings;
  for (const StaticBinding& b : desc.static_bindings) bindings.push_back(b.binding);
  for (const FrameBinding& b : desc.frame_bindings) bindings.push_back(b.binding);
  if (desc.prepass != nullptr) {
    const std::span<const std::uint32_t> only = desc.prepass->prepass_only;
    std::erase_if(bindings, [&](std::uint32_t b) { return std::find(only.begin(), only.end(), b) != only.end(); });
  }
  ODESKIN_ASSIGN_OR_RETURN(d.pipeline_, createSortedPipeline(device, desc.spirv, bindings, desc.texel_bindings,
                                                             desc.push_constant_bytes, desc.frames_in_flight));
  ODESKIN_ASSIGN_OR_RETURN(d.ring_, FrameRing::create(device, FrameRingDesc{desc.frames_in_flight, desc.frame_bytes}));

  // Descriptors are written once: the static buffers never change and each slot keeps its own
  // per-frame buffer, so no descriptor update happens per frame.
  ODESKIN_TRY(bindListed(d.pipeline_, bindings, desc.static_bindings, desc.frame_bindings, d.ring_));
  if (desc.prepass != nullptr) ODESKIN_TRY(d.createPrepass(device, desc));
  return d;
}

Status ComputeDispatcher::createPrepass(const Device& device, const ComputeDispatcherDesc& desc) {
  const ComputePrepassDesc& pre = *desc.prepass;
  ODESKIN_ASSIGN_OR_RETURN(prepass_, createSortedPipeline(device, pre.spirv, pre.bindings, pre.texel_bindings,
                                                          pre.push_constant_bytes, desc.frames_in_flight));
  return bindListed(prepass_, pre.bindings, desc.static_bindings, desc.frame_bindings, ring_);
}

Status bindListed(ComputePipeline& pipeline, std::span<const std::uint32_t> bindings,
                  std::span<const StaticBinding> statics, std::span<const FrameBinding> frame_bindings,
                  const FrameRing& ring) {
  for (const std::uint32_t binding : bindings) {
    const auto is = [binding](const auto& b) { return b.binding == binding; };
    const auto st = std::find_if(statics.begin(), statics.end(), is);
    const auto fr = std::find_if(frame_bindings.begin(), frame_bindings.end(), is);
    for (std::uint32_t s = 0; s < pipeline.setCount(); ++s) {
      if (st != statics.end()) {
        ODESKIN_TRY(pipeline.bindBuffer(s, binding, st->buffer));
      } else if (fr != frame_bindings.end()) {
        ODESKIN_TRY(pipeline.bindBuffer(s, binding, ring.inputBuffer(s), fr->offset, fr->size));
      } else {
        return invalidArgument("compute pipeline: binding " + std::to_string(binding) +
                               " is neither a static nor a per-frame binding");
      }
    }
  }
  return okStatus();
}

ComputeDispatcher& ComputeDispatcher::operator=(ComputeDispatcher&& other) noexcept {
  if (this != &other) {
    // The ring first: its assignment waits for this dispatcher's frames before the pipeline goes.
    ring_ = std::move(other.ring_);
    reuse_stages_ = other.reuse_stages_;
    pipeline_ = std::move(other.pipeline_);
    prepass_ = std::move(other.prepass_);
    slot_ = other.slot_;
  }
  return *this;
}

Result<std::span<std::byte>> ComputeDispatcher::beginFrame() {
  ODESKIN_ASSIGN_OR_RETURN(slot_, ring_.beginFrame());
  return ring_.inputs(slot_);
}

Status ComputeDispatcher::submitFrame(const void* push, std::uint32_t group_count, const void* prepass_push,
                                      std::uint32_t prepass_groups) {
  ODESKIN_ASSIGN_OR_RETURN(VkCommandBuffer cmd, ring_.beginRecording());
  // Frames share the output buffer: the previous frame's shader writes (and anyone's reads of them,
  // e.g. a vertex fetch or a copy) must finish before this frame overwrites it (WAW/WAR).
  recordMemoryBarrier(cmd, reuse_stages_, VK_ACCESS_SHADER_WRITE_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                      VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
  if (prepass_.setCount() > 0 && prepass_groups > 0) {
    prepass_.recordDispatch(cmd, slot_, prepass_push, prepass_groups);
    // The main dispatch reads what the prepass wrote.
    recordMemoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                        VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
  }
  pipeline_.recordDispatch(cmd, slot_, push, group_count);
  // A fence alone does not make device writes visible to the host; this barrier does, so a mapped
  // output can be read right after the wait.
  recordMemoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT, VK_PIPELINE_STAGE_HOST_BIT,
                      VK_ACCESS_HOST_READ_BIT);
  return ring_.submit();
}

}  // namespace odeskin::vk
