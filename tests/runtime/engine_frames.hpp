// SPDX-License-Identifier: MIT
// A game engine's side of VulkanRuntime::recordFrame for the tests: its own command pool, command
// buffers and fences, one of each per frame in flight, submitted on the device's queue.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <vulkan/vulkan.h>

#include "host/device.hpp"
#include "host/vk_handle.hpp"

namespace odeskin::testing {

// An engine's frames in flight; the fences start signalled, as an engine's first frame expects.
class EngineFrames {
 public:
  EngineFrames(const vk::Device& device, std::uint32_t count) : device_(&device) {
    Result<vk::UniqueCommandPool> pool = device.createCommandPool(VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT);
    EXPECT_TRUE(pool.ok());
    pool_ = std::move(pool).value();
    cmds_.resize(count);
    VkCommandBufferAllocateInfo alloc{};
    alloc.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
    alloc.commandPool = pool_.get();
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = count;
    EXPECT_EQ(vkAllocateCommandBuffers(device.handle(), &alloc, cmds_.data()), VK_SUCCESS);
    VkFenceCreateInfo fence_info{};
    fence_info.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
    fence_info.flags = VK_FENCE_CREATE_SIGNALED_BIT;
    for (std::uint32_t j = 0; j < count; ++j) {
      VkFence fence = VK_NULL_HANDLE;
      EXPECT_EQ(vkCreateFence(device.handle(), &fence_info, nullptr, &fence), VK_SUCCESS);
      fences_.emplace_back(device.handle(), fence);
    }
  }
  EngineFrames(const EngineFrames&) = delete;
  EngineFrames& operator=(const EngineFrames&) = delete;
  ~EngineFrames() {
    (void)vkDeviceWaitIdle(device_->handle());
    vkFreeCommandBuffers(device_->handle(), pool_.get(), static_cast<std::uint32_t>(cmds_.size()), cmds_.data());
  }

  // Waits for frame `j`'s previous submission, then begins recording its command buffer.
  VkCommandBuffer begin(std::uint32_t j) {
    waitFor(j);
    VkFence fence = fences_[j].get();
    EXPECT_EQ(vkResetFences(device_->handle(), 1, &fence), VK_SUCCESS);
    EXPECT_EQ(vkResetCommandBuffer(cmds_[j], 0), VK_SUCCESS);
    VkCommandBufferBeginInfo begin_info{};
    begin_info.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
    begin_info.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    EXPECT_EQ(vkBeginCommandBuffer(cmds_[j], &begin_info), VK_SUCCESS);
    return cmds_[j];
  }
  void submit(std::uint32_t j) {
    ASSERT_EQ(vkEndCommandBuffer(cmds_[j]), VK_SUCCESS);
    VkSubmitInfo info{};
    info.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
    info.commandBufferCount = 1;
    info.pCommandBuffers = &cmds_[j];
    ASSERT_TRUE(device_->submit(info, fences_[j].get()).ok());
  }
  void waitFor(std::uint32_t j) { EXPECT_EQ(waitFor(j, UINT64_MAX), VK_SUCCESS); }
  VkResult waitFor(std::uint32_t j, std::uint64_t timeout_ns) {
    VkFence fence = fences_[j].get();
    return vkWaitForFences(device_->handle(), 1, &fence, VK_TRUE, timeout_ns);
  }

 private:
  const vk::Device* device_;
  vk::UniqueCommandPool pool_;
  std::vector<VkCommandBuffer> cmds_;
  std::vector<vk::UniqueFence> fences_;
};

}  // namespace odeskin::testing
