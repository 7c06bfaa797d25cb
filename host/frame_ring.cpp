// SPDX-License-Identifier: MIT
#include "frame_ring.hpp"

#include <algorithm>
#include <cstring>
#include <string>
#include <utility>

#include "compute_pipeline.hpp"
#include "vk_status.hpp"

namespace odeskin::vk {

Result<FrameRing> FrameRing::create(const Device& device, const FrameRingDesc& desc) {
  if (desc.frames_in_flight == 0) return invalidArgument("FrameRing: frames_in_flight is 0");
  FrameRing ring;
  ring.owner_ = &device;
  // Resettable command buffers: per-frame buffers are re-recorded in place instead of reallocated.
  ODESKIN_ASSIGN_OR_RETURN(ring.pool_, device.createCommandPool(VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT));
  ODESKIN_ASSIGN_OR_RETURN(ring.timestamps_, TimestampQueries::create(device, desc.frames_in_flight));
  ODESKIN_ASSIGN_OR_RETURN(ring.finished_, Buffer::create(device, VkDeviceSize{desc.frames_in_flight} * sizeof(std::uint64_t),
                                                          VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::kHostVisible));
  std::memset(ring.finished_.mapped(), 0, ring.finished_.size());
  ring.slots_.resize(desc.frames_in_flight);
  for (Slot& slot : ring.slots_) {
    // Host-visible and mapped for the slot's lifetime: per-frame writes are plain stores.
    if (desc.input_bytes > 0) {
      ODESKIN_ASSIGN_OR_RETURN(slot.inputs, Buffer::create(device, desc.input_bytes, kShaderInputUsage,
                                                           MemoryUse::kHostVisible));
    }
    ODESKIN_ASSIGN_OR_RETURN(VkCommandBuffer cmd, device.allocateCommandBuffer(ring.pool_.get()));
    slot.cmd = UniqueCommandBuffer(device.handle(), ring.pool_.get(), cmd);
    ODESKIN_ASSIGN_OR_RETURN(slot.fence, device.createFence());
  }
  return ring;
}

FrameRing& FrameRing::operator=(FrameRing&& other) noexcept {
  if (this != &other) {
    waitAllNoThrow();
    owner_ = std::exchange(other.owner_, nullptr);
    // Slots (their command buffers) before the pool they came from.
    slots_.clear();
    pool_ = std::move(other.pool_);
    timestamps_ = std::move(other.timestamps_);
    finished_ = std::move(other.finished_);
    slots_ = std::move(other.slots_);
    next_ = other.next_;
    current_ = other.current_;
    last_submitted_ = other.last_submitted_;
    last_gpu_seconds_ = other.last_gpu_seconds_;
  }
  return *this;
}

FrameRing::~FrameRing() { waitAllNoThrow(); }

void FrameRing::waitAllNoThrow() noexcept {
  // Frames recorded into the caller's command buffers and not completed may still run; they were
  // submitted on the device's queue (VulkanRuntime::recordFrame's contract), so its idle is theirs.
  const bool recorded = std::any_of(slots_.begin(), slots_.end(), [](const Slot& s) { return s.recorded != 0; });
  if (recorded) (void)owner_->waitQueueIdle();
  for (Slot& slot : slots_) {
    if (!slot.pending) continue;
    VkFence fence = slot.fence.get();
    // A failure here (device lost) leaves nothing better to do than to go on destroying.
    (void)vkWaitForFences(owner_->handle(), 1, &fence, VK_TRUE, UINT64_MAX);
    slot.pending = false;
  }
}

std::span<std::byte> FrameRing::inputs(std::uint32_t slot) const {
  const Buffer& buffer = slots_[slot].inputs;
  return std::span<std::byte>(buffer.mapped(), buffer.mapped() ? buffer.size() : 0);
}

Status FrameRing::waitSlot(std::uint32_t s) {
  Slot& slot = slots_[s];
  if (slot.recorded != 0) {
    return invalidArgument("FrameRing: slot " + std::to_string(s) +
                           " holds a frame recorded into a command buffer of the caller's, not completed yet");
  }
  if (!slot.pending) return okStatus();
  VkFence fence = slot.fence.get();
  ODESKIN_VK_TRY(vkWaitForFences(owner_->handle(), 1, &fence, VK_TRUE, UINT64_MAX));
  ODESKIN_VK_TRY(vkResetFences(owner_->handle(), 1, &fence));
  slot.pending = false;
  ODESKIN_ASSIGN_OR_RETURN(slot.gpu_seconds, timestamps_.seconds(s));
  last_gpu_seconds_ = slot.gpu_seconds;
  return okStatus();
}

Result<std::uint32_t> FrameRing::beginFrame() {
  current_ = next_;
  // The slot's previous frame (frames_in_flight frames ago) must be done before its inputs change.
  ODESKIN_TRY(waitSlot(current_));
  return current_;
}

Result<VkCommandBuffer> FrameRing::beginRecording() {
  VkCommandBuffer cmd = slots_[current_].cmd.get();
  // Re-recorded every frame (pool created with RESET_COMMAND_BUFFER): tiny, and push constants change.
  ODESKIN_VK_TRY(vkResetCommandBuffer(cmd, 0));
  VkCommandBufferBeginInfo begin{};
  begin.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  ODESKIN_VK_TRY(vkBeginCommandBuffer(cmd, &begin));
  timestamps_.recordBegin(cmd, current_);
  return cmd;
}

Status FrameRing::submit() {
  Slot& slot = slots_[current_];
  VkCommandBuffer cmd = slot.cmd.get();
  timestamps_.recordEnd(cmd, current_);
  ODESKIN_VK_TRY(vkEndCommandBuffer(cmd));
  VkSubmitInfo submit_info{};
  submit_info.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
  submit_info.commandBufferCount = 1;
  submit_info.pCommandBuffers = &cmd;
  ODESKIN_TRY(owner_->submit(submit_info, slot.fence.get()));
  slot.pending = true;
  last_submitted_ = current_;
  next_ = (current_ + 1) % slotCount();
  return okStatus();
}

void FrameRing::endRecordingInto(VkCommandBuffer cmd, std::uint64_t frame) {
  // The word is written after everything recorded before it, so it holding `frame` means the
  // frame's work is done; frame numbers do not repeat, so an old value never passes for it.
  recordMemoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                      VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                      VK_ACCESS_TRANSFER_WRITE_BIT);
  vkCmdUpdateBuffer(cmd, finished_.handle(), VkDeviceSize{current_} * sizeof(frame), sizeof(frame), &frame);
  recordMemoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_HOST_BIT,
                      VK_ACCESS_HOST_READ_BIT);
  timestamps_.recordEnd(cmd, current_);
  slots_[current_].recorded = frame;
  last_submitted_ = current_;
  next_ = (current_ + 1) % slotCount();
}

Status FrameRing::completeRecorded(std::uint32_t s) {
  Slot& slot = slots_[s];
  if (slot.recorded == 0) return okStatus();
  std::uint64_t finished = 0;
  std::memcpy(&finished, finished_.mapped() + std::size_t{s} * sizeof(finished), sizeof(finished));
  if (finished != slot.recorded) {
    return invalidArgument("FrameRing: slot " + std::to_string(s) + "'s frame has not finished on the device");
  }
  slot.recorded = 0;
  // Written at the end of the same command buffer: waiting for it is waiting for the submission's end.
  ODESKIN_ASSIGN_OR_RETURN(slot.gpu_seconds, timestamps_.seconds(s));
  last_gpu_seconds_ = slot.gpu_seconds;
  return okStatus();
}

Status FrameRing::waitAll() {
  // Oldest first, so the newest frame's GPU time is the one left in last_gpu_seconds_.
  const std::uint32_t count = slotCount();
  for (std::uint32_t k = 1; k <= count; ++k) ODESKIN_TRY(waitSlot((last_submitted_ + k) % count));
  return okStatus();
}

void FrameRing::countBuffers(BufferTally& tally) const {
  tally.add(finished_);
  for (const Slot& slot : slots_) tally.add(slot.inputs);
}

}  // namespace odeskin::vk
