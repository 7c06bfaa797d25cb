// SPDX-License-Identifier: MIT
// What GpuDeformer and GpuLbs share: one pipeline, static storage buffers bound once, and a ring of
// frames in flight. Each frame slot owns a persistently-mapped per-frame input buffer, a descriptor
// set, a command buffer, a fence and a timestamp pair, so frame k+1's inputs are written while
// frame k runs and nothing is allocated per frame.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <vulkan/vulkan.h>

#include "buffer.hpp"
#include "compute_pipeline.hpp"
#include "device.hpp"
#include "engine/core/result.hpp"
#include "timestamp_queries.hpp"
#include "vk_handle.hpp"

namespace odeskin::vk {

// A buffer bound to the same binding in every frame slot (uploaded data, the output).
struct StaticBinding {
  std::uint32_t binding = 0;
  VkBuffer buffer = VK_NULL_HANDLE;
};
// A slice of each slot's per-frame buffer bound at `binding`; `offset` a multiple of
// minStorageBufferOffsetAlignment, `size` > 0.
struct FrameBinding {
  std::uint32_t binding = 0;
  VkDeviceSize offset = 0;
  VkDeviceSize size = 0;
};

struct ComputeDispatcherDesc {
  std::span<const std::uint32_t> spirv;
  std::span<const StaticBinding> static_bindings;
  std::span<const FrameBinding> frame_bindings;
  VkDeviceSize frame_bytes = 0;            // per-frame buffer size, > 0 if frame_bindings is not empty
  std::uint32_t push_constant_bytes = 0;
  std::uint32_t frames_in_flight = 2;
};

class ComputeDispatcher {
 public:
  static Result<ComputeDispatcher> create(const Device& device, const ComputeDispatcherDesc& desc);

  ComputeDispatcher() = default;
  ComputeDispatcher(ComputeDispatcher&&) noexcept = default;
  ComputeDispatcher& operator=(ComputeDispatcher&& other) noexcept;
  ComputeDispatcher(const ComputeDispatcher&) = delete;
  ComputeDispatcher& operator=(const ComputeDispatcher&) = delete;
  // Waits for in-flight frames: their command buffers and buffers must not die under the GPU.
  ~ComputeDispatcher();

  // Waits until the next slot's previous frame has finished and returns its mapped per-frame bytes
  // for the caller to fill. Call submitFrame next.
  Result<std::span<std::byte>> beginFrame();
  // Records and submits the slot from beginFrame: `push` and `group_count` workgroups, bracketed by
  // timestamps and by the barriers a shared output buffer needs between frames.
  Status submitFrame(const void* push, std::uint32_t group_count);
  // Waits for every submitted frame and updates lastGpuSeconds().
  Status wait();
  // GPU time of the most recently completed frame in seconds (0 before any, or without timestamps).
  double lastGpuSeconds() const { return last_gpu_seconds_; }

 private:
  struct Slot {
    Buffer inputs;
    UniqueCommandBuffer cmd;
    UniqueFence fence;
    bool pending = false;
  };
  Status retire(std::uint32_t slot);
  void waitAll() noexcept;

  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  VkPipelineStageFlags reuse_stages_ = 0;  // stages that may still use the previous frame's output
  ComputePipeline pipeline_;
  TimestampQueries timestamps_;
  std::vector<Slot> slots_;
  std::uint32_t next_ = 0;     // slot beginFrame hands out
  std::uint32_t current_ = 0;  // slot being filled between beginFrame and submitFrame
  std::uint32_t last_submitted_ = 0;
  double last_gpu_seconds_ = 0.0;
};

}  // namespace odeskin::vk
