// SPDX-License-Identifier: MIT
#include "frame_ring.hpp"

#include <utility>

#include "vk_status.hpp"

namespace odeskin::vk {

Result<FrameRing> FrameRing::create(const Device& device, const FrameRingDesc& desc) {
  if (desc.frames_in_flight == 0) return invalidArgument("FrameRing: frames_in_flight is 0");
  FrameRing ring;
  ring.owner_ = &device;
  // Resettable command buffers: per-frame buffers are re-recorded in place instead of reallocated.
  ODESKIN_ASSIGN_OR_RETURN(ring.pool_, device.createCommandPool(VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT));
  ODESKIN_ASSIGN_OR_RETURN(ring.timestamps_, TimestampQueries::create(device, desc.frames_in_flight));
  ring.slots_.resize(desc.frames_in_flight);
  for (Slot& slot : ring.slots_) {
    // Host-visible and mapped for the slot's lifetime: per-frame writes are plain stores.
    if (desc.input_bytes > 0) {
      ODESKIN_ASSIGN_OR_RETURN(slot.inputs, Buffer::create(device, desc.input_bytes, kShaderInputUsage,
                                                           MemoryUse::kHostVisible));
    }
    VkCommandBufferAllocateInfo alloc{};
    alloc.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
    alloc.commandPool = ring.pool_.get();
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    ODESKIN_VK_TRY(vkAllocateCommandBuffers(device.handle(), &alloc, &cmd));
    slot.cmd = UniqueCommandBuffer(device.handle(), ring.pool_.get(), cmd);
    VkFenceCreateInfo fence_info{};
    fence_info.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
    VkFence fence = VK_NULL_HANDLE;
    ODESKIN_VK_TRY(vkCreateFence(device.handle(), &fence_info, nullptr, &fence));
    slot.fence = UniqueFence(device.handle(), fence);
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

Status FrameRing::waitAll() {
  // Oldest first, so the newest frame's GPU time is the one left in last_gpu_seconds_.
  const std::uint32_t count = slotCount();
  for (std::uint32_t k = 1; k <= count; ++k) ODESKIN_TRY(waitSlot((last_submitted_ + k) % count));
  return okStatus();
}

}  // namespace odeskin::vk
