// SPDX-License-Identifier: MIT
// VulkanRuntime::recordFrame: the runtime's commands recorded into command buffers of an engine's,
// which the engine submits with its own work and reports finished (frameCompleted). The engine
// here is the test: its own command pool, command buffers and fences, a copy of each frame's
// positions standing in for its draws. Everything runs under the validation layer.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/runtime/cpu_runtime.hpp"
#include "host/buffer.hpp"
#include "host/gpu_test_support.hpp"
#include "host/runtime/vulkan_runtime.hpp"
#include "engine_frames.hpp"
#include "runtime_fixtures.hpp"
#include "vulkan_runtime_checks.hpp"

namespace odeskin {
namespace {

using testing::EngineFrames;
using testing::expectSameFrame;
using testing::GpuTest;
using testing::makeAsset;
using testing::read;
using testing::setBoth;
using testing::withCapacity;
using testing::worstGap;

bool mentions(const Status& status, const std::string& text) {
  return status.message().find(text) != std::string::npos;
}

// Records the vertex-input barrier and a copy of instance `instance`'s positions into `to`, as an
// engine's draw would read them, then makes the copy visible to the host.
void recordEngineRead(VkCommandBuffer cmd, const RuntimeFrameBuffers& buffers, const RuntimeOutputBarriers& barriers,
                      std::uint32_t instance, const vk::Buffer& to) {
  barriers.record(cmd);
  VkBufferMemoryBarrier to_transfer = barriers.barriers[0];
  to_transfer.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 1,
                       &to_transfer, 0, nullptr);
  VkBufferCopy region{instance * buffers.instance_stride, 0, buffers.instance_stride};
  vkCmdCopyBuffer(cmd, buffers.positions, to.handle(), 1, &region);
  VkMemoryBarrier to_host{};
  to_host.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
  to_host.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  to_host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &to_host, 0, nullptr, 0,
                       nullptr);
}

std::vector<gpu::Float4> mappedPositions(const vk::Buffer& buffer, std::uint32_t vertices) {
  std::vector<gpu::Float4> out(vertices);
  std::memcpy(out.data(), buffer.mapped(), out.size() * sizeof(gpu::Float4));
  return out;
}

// Six frames, each recorded into the engine's command buffer for its slot with the engine's own
// read of the outputs after it; each checked against the CPU runtime once the engine's fence says
// it is done, both through the runtime's readers and through what the engine's commands copied.
TEST_F(GpuTest, RuntimeRecordsIntoAnEnginesCommandBuffers) {
  const RuntimeAsset asset = makeAsset(testing::cylinderAsset());
  constexpr std::uint32_t kCount = 4;
  constexpr std::uint32_t kFrames = 6;
  Result<VulkanRuntime> gpu = VulkanRuntime::create(device(), asset, withCapacity(kCount));
  Result<CpuRuntime> cpu = CpuRuntime::create(asset, withCapacity(kCount));
  ASSERT_TRUE(gpu.ok() && cpu.ok()) << gpu.status().toString();
  ASSERT_TRUE(gpu->setInstanceCount(kCount).ok() && cpu->setInstanceCount(kCount).ok());
  const std::uint32_t slots = gpu->framesInFlight();
  const VkDeviceSize stride = VkDeviceSize{asset.vertexCount()} * sizeof(gpu::Float4);
  std::vector<vk::Buffer> engine_copies;
  for (std::uint32_t j = 0; j < slots; ++j) {
    Result<vk::Buffer> copy =
        vk::Buffer::create(device(), stride, VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUse::kHostVisible);
    ASSERT_TRUE(copy.ok()) << copy.status().toString();
    engine_copies.push_back(std::move(copy).value());
  }
  EngineFrames engine(device(), slots);

  // Frame f's engine slot j = (f - 1) % slots: waiting for j's fence finishes frame f - slots.
  auto check = [&](std::uint64_t frame) {
    const std::uint32_t j = static_cast<std::uint32_t>((frame - 1) % slots);
    engine.waitFor(j);
    ASSERT_TRUE(gpu->frameCompleted(frame).ok());
    expectSameFrame(*cpu, frame, *gpu, frame, kCount, "recorded frame " + std::to_string(frame));
    const std::uint32_t copied = static_cast<std::uint32_t>(frame % kCount);
    EXPECT_EQ(worstGap(read(*gpu, frame, copied), mappedPositions(engine_copies[j], asset.vertexCount())).gap, 0.0)
        << "the engine's own read of frame " << frame;
    Result<FrameTimes> times = gpu->frameTimes(frame);
    ASSERT_TRUE(times.ok());
    if (device().timestampValidBits() > 0) {
      EXPECT_GT(times->deform_seconds, 0.0);
    }
  };
  for (std::uint64_t f = 1; f <= kFrames; ++f) {
    const std::uint32_t j = static_cast<std::uint32_t>((f - 1) % slots);
    if (f > slots) check(f - slots);
    for (std::uint32_t k = 0; k < kCount; ++k) {
      setBoth(*cpu, *gpu, k, InstanceState::atTime(std::fmod(0.37 * static_cast<double>(f + k), 3.0)).withPreset(static_cast<std::uint32_t>((k + f) % 3)));
    }
    VkCommandBuffer cmd = engine.begin(j);
    Result<std::uint64_t> frame = gpu->recordFrame(cmd);
    ASSERT_TRUE(frame.ok()) << frame.status().toString();
    ASSERT_EQ(*frame, f);
    Result<RuntimeFrameBuffers> buffers = gpu->frameBuffers(f);
    Result<RuntimeOutputBarriers> barriers = gpu->outputBarriers(f);
    ASSERT_TRUE(buffers.ok() && barriers.ok());
    recordEngineRead(cmd, *buffers, *barriers, static_cast<std::uint32_t>(f % kCount), engine_copies[j]);
    engine.submit(j);
    ASSERT_TRUE(cpu->submitFrame().ok());
  }
  for (std::uint64_t f = kFrames - slots + 1; f <= kFrames; ++f) check(f);
  // The engine's frames and the runtime's own mix: a submitted frame after recorded ones.
  for (std::uint32_t k = 0; k < kCount; ++k) setBoth(*cpu, *gpu, k, InstanceState::atTime(2.9 - 0.5 * k));
  Result<std::uint64_t> submitted = gpu->submitFrame();
  ASSERT_TRUE(submitted.ok() && cpu->submitFrame().ok()) << submitted.status().toString();
  expectSameFrame(*cpu, *submitted, *gpu, *submitted, kCount, "submitted after recorded frames");
  ASSERT_TRUE(gpu->wait().ok());
}

// What the engine can get wrong is refused, naming the frame, and never waits for a submission
// the runtime cannot see.
TEST_F(GpuTest, RecordedFramesWaitForTheEnginesWord) {
  const RuntimeAsset asset = makeAsset(testing::cylinderAsset());
  Result<VulkanRuntime> gpu = VulkanRuntime::create(device(), asset, withCapacity(2));
  ASSERT_TRUE(gpu.ok()) << gpu.status().toString();
  ASSERT_TRUE(gpu->setInstanceCount(2).ok());
  EngineFrames engine(device(), 2);
  EXPECT_TRUE(mentions(gpu->recordFrame(VK_NULL_HANDLE).status(), "recordFrame: the command buffer is null"));

  VkCommandBuffer first = engine.begin(0);
  ASSERT_EQ(gpu->recordFrame(first).value(), 1u);
  engine.submit(0);
  VkCommandBuffer second = engine.begin(1);
  ASSERT_EQ(gpu->recordFrame(second).value(), 2u);

  // Frame 1 is submitted, frame 2 not yet: neither may be read, nor their slots taken.
  std::vector<InstanceBounds> bounds(2);
  Status status = gpu->readBounds(1, bounds);
  EXPECT_EQ(status.code(), StatusCode::kInvalidArgument);
  EXPECT_TRUE(mentions(status, "frame 1 was recorded into a command buffer of the engine's and is not completed "
                               "(its outputs cannot be read yet); call frameCompleted(1)"))
      << status.message();
  std::vector<gpu::Float4> out(asset.vertexCount());
  EXPECT_TRUE(mentions(gpu->readPositions(2, 0, out), "frameCompleted(2)"));
  EXPECT_TRUE(mentions(gpu->frameTimes(2).status(), "frameCompleted(2)"));
  EXPECT_TRUE(mentions(gpu->wait(), "(wait() cannot wait for it); call frameCompleted(1)"));
  status = gpu->recordFrame(second).status();
  EXPECT_TRUE(mentions(status, "frame 1 was recorded into a command buffer of the engine's and is not completed "
                               "(frame 3 needs its slot)"))
      << status.message();
  EXPECT_TRUE(mentions(gpu->submitFrame().status(), "(frame 3 needs its slot)"));
  EXPECT_EQ(gpu->lastFrame(), 2u);  // the refused frames took nothing
  EXPECT_TRUE(mentions(gpu->frameCompleted(3), "frame 3 is not held"));
  EXPECT_TRUE(mentions(gpu->frameCompleted(0), "frame 0 is not held"));

  engine.submit(1);
  engine.waitFor(0);
  ASSERT_TRUE(gpu->frameCompleted(1).ok());
  ASSERT_TRUE(gpu->frameCompleted(1).ok());  // twice is harmless
  ASSERT_TRUE(gpu->readBounds(1, bounds).ok());
  engine.waitFor(1);
  ASSERT_TRUE(gpu->frameCompleted(2).ok());
  Result<std::uint64_t> third = gpu->submitFrame();
  ASSERT_TRUE(third.ok()) << third.status().toString();
  EXPECT_TRUE(mentions(gpu->frameCompleted(*third), "frame 3 was submitted by submitFrame()"));
  ASSERT_TRUE(gpu->wait().ok());
}

// frameCompleted before the frame's commands have run is refused, not taken on trust: here the
// engine has not even submitted them. (A call while the submission still runs reads the same
// unwritten word; that moment cannot be staged reliably in a test.)
TEST_F(GpuTest, FrameCompletedTooEarlyIsRefused) {
  const RuntimeAsset asset = makeAsset(testing::cylinderAsset());
  Result<VulkanRuntime> gpu = VulkanRuntime::create(device(), asset, withCapacity(3));
  ASSERT_TRUE(gpu.ok()) << gpu.status().toString();
  ASSERT_TRUE(gpu->setInstanceCount(3).ok());
  EngineFrames engine(device(), 1);
  for (std::uint64_t frame = 1; frame <= 3; ++frame) {
    VkCommandBuffer cmd = engine.begin(0);
    ASSERT_EQ(gpu->recordFrame(cmd).value(), frame);
    const Status early = gpu->frameCompleted(frame);
    EXPECT_EQ(early.code(), StatusCode::kInvalidArgument);
    EXPECT_TRUE(mentions(early, "frameCompleted: frame " + std::to_string(frame) +
                                    " has not finished on the device (its last command has not run)"))
        << early.message();
    engine.submit(0);
    engine.waitFor(0);
    ASSERT_TRUE(gpu->frameCompleted(frame).ok()) << "frame " << frame;
  }
  std::vector<InstanceBounds> bounds(3);
  ASSERT_TRUE(gpu->readBounds(3, bounds).ok());
}

// An engine that drops the runtime while a recorded frame it submitted may still run (it never
// waited for its fence): the runtime waits for the queue before its buffers go. The validation
// layer reports buffers destroyed while a submission that uses them is pending.
TEST_F(GpuTest, ARuntimeDroppedWithARecordedFrameInFlightWaitsForIt) {
  const RuntimeAsset asset = makeAsset(testing::cylinderAsset());
  EngineFrames engine(device(), 1);  // outlives the runtime, as an engine's frames do
  std::optional<VulkanRuntime> gpu;
  Result<VulkanRuntime> created = VulkanRuntime::create(device(), asset, withCapacity(4));
  ASSERT_TRUE(created.ok()) << created.status().toString();
  gpu.emplace(std::move(created).value());
  ASSERT_TRUE(gpu->setInstanceCount(4).ok());
  ASSERT_TRUE(gpu->recordFrame(engine.begin(0)).ok());
  engine.submit(0);
  gpu.reset();
}

}  // namespace
}  // namespace odeskin
