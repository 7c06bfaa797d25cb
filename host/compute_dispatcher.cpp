// SPDX-License-Identifier: MIT
#include "compute_dispatcher.hpp"

#include <utility>

#include "vk_status.hpp"

namespace odeskin::vk {

Result<ComputeDispatcher> ComputeDispatcher::create(const Device& device, const ComputeDispatcherDesc& desc) {
  if (desc.frames_in_flight == 0) return invalidArgument("ComputeDispatcher: frames_in_flight is 0");
  ComputeDispatcher d;
  d.device_ = device.handle();
  d.queue_ = device.queue();
  d.reuse_stages_ = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT;
  // A renderer on a graphics queue may fetch the output as vertices; that stage only exists there.
  if (device.queueFlags() & VK_QUEUE_GRAPHICS_BIT) d.reuse_stages_ |= VK_PIPELINE_STAGE_VERTEX_INPUT_BIT;

  std::vector<std::uint32_t> bindings;
  for (const StaticBinding& b : desc.static_bindings) bindings.push_back(b.binding);
  for (const FrameBinding& b : desc.frame_bindings) bindings.push_back(b.binding);
  ComputePipelineDesc pipeline_desc;
  pipeline_desc.spirv = desc.spirv;
  pipeline_desc.storage_bindings = bindings;
  pipeline_desc.push_constant_bytes = desc.push_constant_bytes;
  pipeline_desc.descriptor_set_count = desc.frames_in_flight;
  ODESKIN_ASSIGN_OR_RETURN(d.pipeline_, ComputePipeline::create(device, pipeline_desc));
  ODESKIN_ASSIGN_OR_RETURN(d.timestamps_, TimestampQueries::create(device, desc.frames_in_flight));

  d.slots_.resize(desc.frames_in_flight);
  for (std::uint32_t s = 0; s < desc.frames_in_flight; ++s) {
    Slot& slot = d.slots_[s];
    // Host-visible and mapped for the slot's lifetime: per-frame writes are plain memcpy.
    if (desc.frame_bytes > 0) {
      ODESKIN_ASSIGN_OR_RETURN(slot.inputs, Buffer::create(device, desc.frame_bytes,
                                                           VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                                           MemoryUse::kHostVisible));
    }
    VkCommandBufferAllocateInfo alloc{};
    alloc.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
    alloc.commandPool = device.commandPool();
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    ODESKIN_VK_TRY(vkAllocateCommandBuffers(device.handle(), &alloc, &cmd));
    slot.cmd = UniqueCommandBuffer(device.handle(), device.commandPool(), cmd);
    VkFenceCreateInfo fence_info{};
    fence_info.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
    VkFence fence = VK_NULL_HANDLE;
    ODESKIN_VK_TRY(vkCreateFence(device.handle(), &fence_info, nullptr, &fence));
    slot.fence = UniqueFence(device.handle(), fence);

    // Descriptors are written once: the static buffers never change and each slot keeps its own
    // per-frame buffer, so no descriptor update happens per frame.
    for (const StaticBinding& b : desc.static_bindings) d.pipeline_.bindBuffer(s, b.binding, b.buffer);
    for (const FrameBinding& b : desc.frame_bindings) {
      d.pipeline_.bindBuffer(s, b.binding, slot.inputs.handle(), b.offset, b.size);
    }
  }
  return d;
}

ComputeDispatcher& ComputeDispatcher::operator=(ComputeDispatcher&& other) noexcept {
  if (this != &other) {
    waitAll();
    device_ = std::exchange(other.device_, VK_NULL_HANDLE);
    queue_ = std::exchange(other.queue_, VK_NULL_HANDLE);
    reuse_stages_ = other.reuse_stages_;
    pipeline_ = std::move(other.pipeline_);
    timestamps_ = std::move(other.timestamps_);
    slots_ = std::move(other.slots_);
    next_ = other.next_;
    current_ = other.current_;
    last_submitted_ = other.last_submitted_;
    last_gpu_seconds_ = other.last_gpu_seconds_;
  }
  return *this;
}

ComputeDispatcher::~ComputeDispatcher() { waitAll(); }

void ComputeDispatcher::waitAll() noexcept {
  for (Slot& slot : slots_) {
    if (!slot.pending) continue;
    VkFence fence = slot.fence.get();
    // A failure here (device lost) leaves nothing better to do than to go on destroying.
    (void)vkWaitForFences(device_, 1, &fence, VK_TRUE, UINT64_MAX);
    slot.pending = false;
  }
}

Status ComputeDispatcher::retire(std::uint32_t s) {
  Slot& slot = slots_[s];
  if (!slot.pending) return okStatus();
  VkFence fence = slot.fence.get();
  ODESKIN_VK_TRY(vkWaitForFences(device_, 1, &fence, VK_TRUE, UINT64_MAX));
  ODESKIN_VK_TRY(vkResetFences(device_, 1, &fence));
  slot.pending = false;
  ODESKIN_ASSIGN_OR_RETURN(last_gpu_seconds_, timestamps_.seconds(s));
  return okStatus();
}

Result<std::span<std::byte>> ComputeDispatcher::beginFrame() {
  current_ = next_;
  // The slot's previous frame (frames_in_flight frames ago) must be done before its inputs change.
  ODESKIN_TRY(retire(current_));
  Slot& slot = slots_[current_];
  return std::span<std::byte>(slot.inputs.mapped(), slot.inputs.mapped() ? slot.inputs.size() : 0);
}

Status ComputeDispatcher::submitFrame(const void* push, std::uint32_t group_count) {
  Slot& slot = slots_[current_];
  VkCommandBuffer cmd = slot.cmd.get();
  // Re-recorded every frame (pool created with RESET_COMMAND_BUFFER): tiny, and push constants change.
  ODESKIN_VK_TRY(vkResetCommandBuffer(cmd, 0));
  VkCommandBufferBeginInfo begin{};
  begin.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  ODESKIN_VK_TRY(vkBeginCommandBuffer(cmd, &begin));
  timestamps_.recordBegin(cmd, current_);

  // Frames share the output buffer: the previous frame's shader writes (and anyone's reads of them,
  // e.g. a vertex fetch or a copy) must finish before this frame overwrites it (WAW/WAR).
  VkMemoryBarrier before{};
  before.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
  before.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
  before.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
  vkCmdPipelineBarrier(cmd, reuse_stages_, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1, &before, 0, nullptr, 0,
                       nullptr);
  pipeline_.recordDispatch(cmd, current_, push, group_count);
  // A fence alone does not make device writes visible to the host; this barrier does, so a mapped
  // output can be read right after the wait.
  VkMemoryBarrier after{};
  after.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
  after.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
  after.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &after, 0,
                       nullptr, 0, nullptr);
  timestamps_.recordEnd(cmd, current_);
  ODESKIN_VK_TRY(vkEndCommandBuffer(cmd));

  // Host writes to the coherent per-frame buffer become visible to the device at submission.
  VkSubmitInfo submit{};
  submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &cmd;
  ODESKIN_VK_TRY(vkQueueSubmit(queue_, 1, &submit, slot.fence.get()));
  slot.pending = true;
  last_submitted_ = current_;
  next_ = (current_ + 1) % static_cast<std::uint32_t>(slots_.size());
  return okStatus();
}

Status ComputeDispatcher::wait() {
  // Oldest first, so the newest frame's GPU time is the one left in last_gpu_seconds_.
  std::uint32_t count = static_cast<std::uint32_t>(slots_.size());
  for (std::uint32_t k = 1; k <= count; ++k) ODESKIN_TRY(retire((last_submitted_ + k) % count));
  return okStatus();
}

}  // namespace odeskin::vk
