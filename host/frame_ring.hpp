// SPDX-License-Identifier: MIT
// A ring of frames in flight, the one implementation of double buffering on the GPU side: each
// slot owns a persistently-mapped per-frame input buffer, a command buffer, a fence and a timestamp
// pair, so frame k+1's inputs are written while frame k runs and nothing is allocated per frame.
// Users: ComputeDispatcher (GpuDeformer, GpuLbs) and host/runtime's VulkanRuntime.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <vulkan/vulkan.h>

#include "buffer.hpp"
#include "device.hpp"
#include "engine/core/result.hpp"
#include "timestamp_queries.hpp"
#include "vk_handle.hpp"

namespace odeskin::vk {

struct FrameRingDesc {
  std::uint32_t frames_in_flight = 2;  // >= 1
  VkDeviceSize input_bytes = 0;        // per-slot mapped input buffer; 0 for none
};

class FrameRing {
 public:
  // kInvalidArgument for frames_in_flight = 0; kDeviceError / kUnavailable from the driver.
  static Result<FrameRing> create(const Device& device, const FrameRingDesc& desc);

  FrameRing() = default;
  FrameRing(FrameRing&&) noexcept = default;
  FrameRing& operator=(FrameRing&& other) noexcept;
  FrameRing(const FrameRing&) = delete;
  FrameRing& operator=(const FrameRing&) = delete;
  // Waits for in-flight frames: their command buffers and inputs must not die under the GPU (and
  // for the queue to idle when a recorded frame is not completed).
  ~FrameRing();

  std::uint32_t slotCount() const { return static_cast<std::uint32_t>(slots_.size()); }
  // The slot's input buffer (bind its slices once; its contents change every frame).
  VkBuffer inputBuffer(std::uint32_t slot) const { return slots_[slot].inputs.handle(); }
  // The slot's mapped input bytes (empty without inputs).
  std::span<std::byte> inputs(std::uint32_t slot) const;

  // Waits until the next slot's previous frame has finished and returns that slot; the caller
  // fills inputs(slot), then beginRecording() and submit(). Slots are handed out 0, 1, ..., n-1, 0, ...
  Result<std::uint32_t> beginFrame();
  // Resets and begins the current slot's command buffer and writes its begin timestamp.
  Result<VkCommandBuffer> beginRecording();
  // Writes the end timestamp, ends the command buffer and submits it with the slot's fence.
  // Host writes to the mapped (coherent) inputs become visible to the device at this submission.
  Status submit();

  // Instead of beginRecording() and submit(), a frame recorded into a command buffer the caller
  // submits (VulkanRuntime::recordFrame): beginRecordingInto writes the current slot's begin mark
  // into `cmd`, the caller records its work, endRecordingInto writes the end mark and `frame` (a
  // number unique to this frame) into the slot's word of a host-visible buffer once all earlier
  // work in `cmd` is done, and moves on to the next slot. Only the caller knows when its submission
  // finished, so the slot stays busy until it says so with completeRecorded(slot): that checks the
  // slot's word, refusing (kInvalidArgument) while it does not hold the frame yet (the submission
  // has not finished, or was never made), then reads the frame's GPU time.
  void beginRecordingInto(VkCommandBuffer cmd) const { timestamps_.recordBegin(cmd, current_); }
  void endRecordingInto(VkCommandBuffer cmd, std::uint64_t frame);
  Status completeRecorded(std::uint32_t slot);
  bool awaitsCompletion(std::uint32_t slot) const { return slots_[slot].recorded != 0; }

  // Waits for slot `slot`'s frame (nothing if none is pending) and reads its GPU time;
  // kInvalidArgument for a recorded frame not completed yet.
  Status waitSlot(std::uint32_t slot);
  // Waits for every submitted frame, oldest first.
  Status waitAll();
  // GPU seconds of `slot`'s finished frame, and of the most recently finished one (0 before any,
  // or without timestamps).
  double gpuSeconds(std::uint32_t slot) const { return slots_[slot].gpu_seconds; }
  double lastGpuSeconds() const { return last_gpu_seconds_; }
  // Adds the ring's buffers (every slot's inputs, the completion words) to `tally`.
  void countBuffers(BufferTally& tally) const;

 private:
  struct Slot {
    Buffer inputs;
    UniqueCommandBuffer cmd;
    UniqueFence fence;
    bool pending = false;   // submitted with the fence, not waited for yet
    std::uint64_t recorded = 0;  // frame recorded into the caller's command buffer, not completed yet
    double gpu_seconds = 0.0;
  };
  void waitAllNoThrow() noexcept;

  const Device* owner_ = nullptr;  // waits and submits through it (one thread at a time on its queue)
  // The ring's own: a command pool may be used by one thread at a time, and rings on one device
  // may be driven from different threads. Before slots_, so their command buffers go first.
  UniqueCommandPool pool_;
  TimestampQueries timestamps_;
  Buffer finished_;  // host-visible: per slot, the last recorded frame whose commands completed
  std::vector<Slot> slots_;
  std::uint32_t next_ = 0;     // slot beginFrame hands out
  std::uint32_t current_ = 0;  // slot being filled between beginFrame and submit
  std::uint32_t last_submitted_ = 0;
  double last_gpu_seconds_ = 0.0;
};

}  // namespace odeskin::vk
