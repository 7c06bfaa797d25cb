// SPDX-License-Identifier: MIT
// One compute pipeline on a FrameRing: static storage buffers bound once, slices of each slot's
// mapped per-frame buffer bound once per slot, and one dispatch per frame (optionally after a
// prepass that writes one of its inputs), bracketed by the barriers a shared output buffer needs
// between frames. What GpuDeformer and GpuLbs (through SingleMeshDispatch) run on.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include <vulkan/vulkan.h>

#include "compute_pipeline.hpp"
#include "device.hpp"
#include "engine/core/result.hpp"
#include "frame_ring.hpp"

namespace odeskin::vk {

// A buffer bound to the same binding in every frame slot (uploaded data, the output).
struct StaticBinding {
  std::uint32_t binding = 0;
  VkBuffer buffer = VK_NULL_HANDLE;
};
// A slice of each slot's per-frame buffer bound at `binding`; `offset` a multiple of
// minStorageBufferOffsetAlignment and minTexelBufferOffsetAlignment, `size` > 0.
struct FrameBinding {
  std::uint32_t binding = 0;
  VkDeviceSize offset = 0;
  VkDeviceSize size = 0;
};

// A pass recorded before the main dispatch in the same command buffer (fold_series.comp before a
// deformation), on its own pipeline over the same static and per-frame buffers: it binds those of
// `bindings` (each must be one of them), reading `texel_bindings` as texel buffers.
struct ComputePrepassDesc {
  std::span<const std::uint32_t> spirv;
  std::span<const std::uint32_t> bindings;
  std::span<const TexelBinding> texel_bindings;
  std::uint32_t push_constant_bytes = 0;
  // Static or per-frame bindings that only the prepass reads: the main pipeline's layout leaves
  // them out, so its descriptor sets hold just what its shader declares.
  std::span<const std::uint32_t> prepass_only;
};

struct ComputeDispatcherDesc {
  std::span<const std::uint32_t> spirv;
  std::span<const StaticBinding> static_bindings;
  std::span<const FrameBinding> frame_bindings;
  // Which of those bindings the shader reads as uniform texel buffers (the rest are storage
  // buffers); entries for bindings not used here are ignored.
  std::span<const TexelBinding> texel_bindings;
  VkDeviceSize frame_bytes = 0;            // per-frame buffer size, > 0 if frame_bindings is not empty
  std::uint32_t push_constant_bytes = 0;
  std::uint32_t frames_in_flight = 2;
  const ComputePrepassDesc* prepass = nullptr;  // optional; read during create() only
};

// Points each of `bindings` in descriptor set k of `pipeline` (every k) at the static buffer of that
// number, or else at its slice of ring slot k's per-frame buffer; kInvalidArgument naming a binding
// in neither. `ring` needs as many slots as `pipeline` has sets.
Status bindListed(ComputePipeline& pipeline, std::span<const std::uint32_t> bindings,
                  std::span<const StaticBinding> statics, std::span<const FrameBinding> frame_bindings,
                  const FrameRing& ring);

// Stages that may still read or write a deformer's output from an earlier frame on this queue:
// compute and transfer (readbacks), and vertex fetch where the queue can draw.
VkPipelineStageFlags outputReuseStages(const Device& device);

class ComputeDispatcher {
 public:
  static Result<ComputeDispatcher> create(const Device& device, const ComputeDispatcherDesc& desc);

  ComputeDispatcher() = default;
  ComputeDispatcher(ComputeDispatcher&&) noexcept = default;
  ComputeDispatcher& operator=(ComputeDispatcher&& other) noexcept;
  ComputeDispatcher(const ComputeDispatcher&) = delete;
  ComputeDispatcher& operator=(const ComputeDispatcher&) = delete;

  // Waits until the next slot's previous frame has finished and returns its mapped per-frame bytes
  // for the caller to fill. Call submitFrame next.
  Result<std::span<std::byte>> beginFrame();
  // Records and submits the slot from beginFrame: `push` and `group_count` workgroups, bracketed by
  // timestamps and by the barriers a shared output buffer needs between frames. With a prepass,
  // `prepass_groups` workgroups of it with `prepass_push` come first, and the main dispatch reads
  // what they wrote.
  Status submitFrame(const void* push, std::uint32_t group_count, const void* prepass_push = nullptr,
                     std::uint32_t prepass_groups = 0);
  // Waits for every submitted frame and updates lastGpuSeconds().
  Status wait() { return ring_.waitAll(); }
  // GPU time of the most recently completed frame in seconds (0 before any, or without timestamps).
  double lastGpuSeconds() const { return ring_.lastGpuSeconds(); }

 private:
  Status createPrepass(const Device& device, const ComputeDispatcherDesc& desc);

  VkPipelineStageFlags reuse_stages_ = 0;
  ComputePipeline pipeline_;
  ComputePipeline prepass_;  // without a prepass: no sets
  std::uint32_t slot_ = 0;   // from the last beginFrame
  // Last, so it is destroyed first: it waits for in-flight frames before the pipeline goes.
  FrameRing ring_;
};

}  // namespace odeskin::vk
