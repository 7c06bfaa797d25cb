// SPDX-License-Identifier: MIT
#include "engine_submissions.hpp"

#include <string>
#include <utility>

#include "host/vk_status.hpp"

namespace odeskin {

Result<EngineSubmissions> EngineSubmissions::create(const vk::Device& device, VulkanRuntime& runtime) {
  EngineSubmissions s(device, runtime);
  ODESKIN_ASSIGN_OR_RETURN(s.pool_, device.createCommandPool(VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT));
  s.slots_.resize(runtime.framesInFlight());
  for (Slot& slot : s.slots_) {
    VkCommandBufferAllocateInfo alloc{};
    alloc.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
    alloc.commandPool = s.pool_.get();
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    ODESKIN_VK_TRY(vkAllocateCommandBuffers(device.handle(), &alloc, &cmd));
    slot.cmd = vk::UniqueCommandBuffer(device.handle(), s.pool_.get(), cmd);
    VkFenceCreateInfo fence_info{};
    fence_info.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
    VkFence fence = VK_NULL_HANDLE;
    ODESKIN_VK_TRY(vkCreateFence(device.handle(), &fence_info, nullptr, &fence));
    slot.fence = vk::UniqueFence(device.handle(), fence);
  }
  return s;
}

EngineSubmissions::~EngineSubmissions() {
  for (Slot& slot : slots_) (void)waitFor(slot);
}

Status EngineSubmissions::waitFor(Slot& slot) const {
  if (!slot.pending) return okStatus();
  VkFence fence = slot.fence.get();
  ODESKIN_VK_TRY(vkWaitForFences(device_->handle(), 1, &fence, VK_TRUE, UINT64_MAX));
  ODESKIN_VK_TRY(vkResetFences(device_->handle(), 1, &fence));
  slot.pending = false;
  return okStatus();
}

// [runtime-snippet]
Result<std::uint64_t> EngineSubmissions::record() {
  VulkanRuntime& rt = *runtime_;
  Slot& slot = slots_[next_];
  next_ = (next_ + 1) % static_cast<std::uint32_t>(slots_.size());
  // The engine's frame pacing: this command buffer's last submission has finished, and with it
  // the runtime's frame inside; saying so frees that frame's slot in the runtime.
  ODESKIN_TRY(waitFor(slot));
  if (slot.frame != 0) ODESKIN_TRY(rt.frameCompleted(slot.frame));
  VkCommandBuffer cmd = slot.cmd.get();
  ODESKIN_VK_TRY(vkResetCommandBuffer(cmd, 0));
  VkCommandBufferBeginInfo begin{};
  begin.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  ODESKIN_VK_TRY(vkBeginCommandBuffer(cmd, &begin));
  ODESKIN_ASSIGN_OR_RETURN(const std::uint64_t frame, rt.recordFrame(cmd));
  ODESKIN_ASSIGN_OR_RETURN(const RuntimeOutputBarriers barriers, rt.outputBarriers(frame));
  barriers.record(cmd);
  // The engine's render pass would follow: bind rt.frameBuffers(frame)->positions (and normals) at
  // k x instance_stride for instance k and draw the asset's triangles.
  ODESKIN_VK_TRY(vkEndCommandBuffer(cmd));
  VkSubmitInfo submit{};
  submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &cmd;
  ODESKIN_TRY(device_->submit(submit, slot.fence.get()));  // vkQueueSubmit on the device's queue
  slot.pending = true;
  slot.frame = frame;
  return frame;
}
// [runtime-snippet]

Status EngineSubmissions::complete(std::uint64_t frame) {
  for (Slot& slot : slots_) {
    if (slot.frame != frame) continue;
    ODESKIN_TRY(waitFor(slot));
    return runtime_->frameCompleted(frame);
  }
  return invalidArgument("engine submissions: frame " + std::to_string(frame) + " is in none of them");
}

}  // namespace odeskin
