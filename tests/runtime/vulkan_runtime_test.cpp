// SPDX-License-Identifier: MIT
// VulkanRuntime against CpuRuntime (the instanced shaders' reference) under the validation layer:
// positions, normals and bounds as vulkan_runtime_checks.hpp says. Also double buffering, instance
// counts 0, 1 and many, the engine's own device, two threads, and bad input.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "engine/runtime/cpu_runtime.hpp"
#include "host/gpu_test_support.hpp"
#include "host/runtime/vulkan_runtime.hpp"
#include "runtime_fixtures.hpp"
#include "vulkan_runtime_checks.hpp"

namespace odeskin {
namespace {

using testing::expectSameFrame;
using testing::GpuTest;
using testing::makeAsset;
using testing::read;
using testing::setBoth;
using testing::withCapacity;
using testing::worstGap;

TEST_F(GpuTest, RuntimeMatchesTheCpuRuntimeOnTheCat) {
  const RuntimeAsset asset = makeAsset(testing::catAsset());
  constexpr std::uint32_t kCount = 12;
  Result<VulkanRuntime> gpu = VulkanRuntime::create(device(), asset, withCapacity(kCount));
  ASSERT_TRUE(gpu.ok()) << gpu.status().toString();
  Result<CpuRuntime> cpu = CpuRuntime::create(asset, withCapacity(kCount));
  ASSERT_TRUE(cpu.ok());
  ASSERT_TRUE(gpu->setInstanceCount(kCount).ok());
  ASSERT_TRUE(cpu->setInstanceCount(kCount).ok());
  std::vector<gpu::BoneMatrix> bones(asset.boneCount());
  asset.bonesAt(5, 0.25, bones);
  const auto world = testing::placed(bones, 1.1, Vec3(-2.0, 0.5, 4.0));
  for (std::uint32_t k = 0; k < kCount; ++k) {
    InstanceState state = k % 4 == 3 ? InstanceState::atSegment(k % 9, 0.5 * (k % 3)) : InstanceState::atTime(0.77 * k);
    state = state.withPreset(k % 3);
    if (k % 5 == 1) state = state.withBones(world);
    setBoth(*cpu, *gpu, k, state);
  }
  Result<std::uint64_t> cpu_frame = cpu->submitFrame();
  Result<std::uint64_t> gpu_frame = gpu->submitFrame();
  ASSERT_TRUE(cpu_frame.ok() && gpu_frame.ok()) << gpu_frame.status().toString();
  expectSameFrame(*cpu, *cpu_frame, *gpu, *gpu_frame, kCount, "cat, 12 instances");
  Result<FrameTimes> times = gpu->frameTimes(*gpu_frame);
  ASSERT_TRUE(times.ok());
  EXPECT_GT(times->deform_seconds, 0.0);  // lavapipe has timestamps
  EXPECT_LT(times->deform_seconds, 10.0);
}

// A game engine's own device (here made by the test as an engine would): the runtime works on it,
// its buffers are that device's, and dropping odeskin's wrapper leaves the device usable. The
// validation layer reports any object odeskin left on it when the engine destroys it.
TEST_F(GpuTest, RuntimeRunsOnAnEnginesOwnDevice) {
  float priority = 1.0f;
  VkDeviceQueueCreateInfo queue_info{};
  queue_info.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO;
  queue_info.queueFamilyIndex = device().queueFamily();
  queue_info.queueCount = 1;
  queue_info.pQueuePriorities = &priority;
  VkDeviceCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO;
  info.queueCreateInfoCount = 1;
  info.pQueueCreateInfos = &queue_info;
  VkDevice engine_device = VK_NULL_HANDLE;
  ASSERT_EQ(vkCreateDevice(device().physicalDevice(), &info, nullptr, &engine_device), VK_SUCCESS);

  vk::ExternalDevice external{device().physicalDevice(), engine_device, device().queueFamily(), 0};
  {
    Result<vk::Device> adopted = vk::Device::adopt(external);
    ASSERT_TRUE(adopted.ok()) << adopted.status().toString();
    EXPECT_FALSE(adopted->ownsDevice());
    EXPECT_EQ(adopted->handle(), engine_device);
    const RuntimeAsset asset = makeAsset(testing::cylinderAsset());
    Result<VulkanRuntime> gpu = VulkanRuntime::create(*adopted, asset, withCapacity(4));
    Result<CpuRuntime> cpu = CpuRuntime::create(asset, withCapacity(4));
    ASSERT_TRUE(gpu.ok() && cpu.ok()) << gpu.status().toString();
    ASSERT_TRUE(gpu->setInstanceCount(4).ok() && cpu->setInstanceCount(4).ok());
    for (std::uint32_t k = 0; k < 4; ++k) setBoth(*cpu, *gpu, k, InstanceState::atTime(0.6 * k).withPreset(k % 3));
    Result<std::uint64_t> cpu_frame = cpu->submitFrame();
    Result<std::uint64_t> gpu_frame = gpu->submitFrame();
    ASSERT_TRUE(cpu_frame.ok() && gpu_frame.ok()) << gpu_frame.status().toString();
    expectSameFrame(*cpu, *cpu_frame, *gpu, *gpu_frame, 4, "cylinder on the engine's device");
    Result<RuntimeFrameBuffers> buffers = gpu->frameBuffers(*gpu_frame);
    ASSERT_TRUE(buffers.ok());
    EXPECT_NE(buffers->positions, VK_NULL_HANDLE);
  }  // the runtime, then odeskin's wrapper, go; the device stays

  // Still the engine's, and alive: it makes and drops an object, then is destroyed by its owner.
  VkCommandPoolCreateInfo pool_info{};
  pool_info.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
  pool_info.queueFamilyIndex = device().queueFamily();
  VkCommandPool pool = VK_NULL_HANDLE;
  EXPECT_EQ(vkCreateCommandPool(engine_device, &pool_info, nullptr, &pool), VK_SUCCESS);
  vkDestroyCommandPool(engine_device, pool, nullptr);
  EXPECT_EQ(vkDeviceWaitIdle(engine_device), VK_SUCCESS);

  // What an engine can get wrong is named.
  vk::ExternalDevice no_family = external;
  no_family.queue_family = 99;
  Result<vk::Device> bad = vk::Device::adopt(no_family);
  EXPECT_EQ(bad.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(bad.status().message().find("queue family 99 does not exist"), std::string::npos) << bad.status().message();
  // One past the family's last queue: lavapipe's family has 1 queue, an NVIDIA GPU's 16. An index
  // the family has but the engine did not create cannot be detected (Vulkan cannot be asked).
  std::uint32_t family_count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(device().physicalDevice(), &family_count, nullptr);
  std::vector<VkQueueFamilyProperties> families(family_count);
  vkGetPhysicalDeviceQueueFamilyProperties(device().physicalDevice(), &family_count, families.data());
  const std::uint32_t queues = families.at(device().queueFamily()).queueCount;
  vk::ExternalDevice no_queue = external;
  no_queue.queue_index = queues;
  bad = vk::Device::adopt(no_queue);
  const std::string expected = "has " + std::to_string(queues) + " queues, not queue " + std::to_string(queues);
  EXPECT_NE(bad.status().message().find(expected), std::string::npos) << bad.status().message();
  EXPECT_EQ(vk::Device::adopt(vk::ExternalDevice{}).status().code(), StatusCode::kInvalidArgument);
  vkDestroyDevice(engine_device, nullptr);
}

// One device, two runtimes (two assets, say), each driven by its own thread as the threading rules
// allow: the device's queue and command pool are shared, and Vulkan requires both to be used by one
// thread at a time. The validation layer's thread checks report any overlap.
TEST_F(GpuTest, RuntimesSharingADeviceRunOnTwoThreads) {
  const RuntimeAsset asset = makeAsset(testing::cylinderAsset());
  Result<CpuRuntime> cpu = CpuRuntime::create(asset, withCapacity(3));
  ASSERT_TRUE(cpu.ok());
  ASSERT_TRUE(cpu->setInstanceCount(3).ok());
  for (std::uint32_t k = 0; k < 3; ++k) ASSERT_TRUE(cpu->setInstance(k, InstanceState::atTime(0.9 * k)).ok());
  Result<std::uint64_t> cpu_frame = cpu->submitFrame();
  ASSERT_TRUE(cpu_frame.ok());
  std::vector<Result<VulkanRuntime>> runtimes;
  runtimes.reserve(2);
  for (int r = 0; r < 2; ++r) runtimes.push_back(VulkanRuntime::create(device(), asset, withCapacity(3)));
  for (Result<VulkanRuntime>& rt : runtimes) {
    ASSERT_TRUE(rt.ok()) << rt.status().toString();
    ASSERT_TRUE(rt->setInstanceCount(3).ok());
    for (std::uint32_t k = 0; k < 3; ++k) ASSERT_TRUE(rt->setInstance(k, InstanceState::atTime(0.9 * k)).ok());
  }
  std::vector<Status> results(2);
  std::vector<std::thread> threads;
  threads.reserve(2);
  for (int r = 0; r < 2; ++r) {
    threads.emplace_back([&, r] {
      for (int frame = 0; frame < 200 && results[r].ok(); ++frame) {
        Result<std::uint64_t> submitted = runtimes[r]->submitFrame();
        results[r] = submitted.ok() ? okStatus() : submitted.status();
      }
      if (results[r].ok()) results[r] = runtimes[r]->wait();
    });
  }
  for (std::thread& t : threads) t.join();
  for (int r = 0; r < 2; ++r) {
    ASSERT_TRUE(results[r].ok()) << results[r].toString();
    expectSameFrame(*cpu, *cpu_frame, *runtimes[r], runtimes[r]->lastFrame(), 3, "runtime " + std::to_string(r));
  }
}

TEST_F(GpuTest, RuntimeMatchesTheCpuRuntimeWithDualQuaternions) {
  const RuntimeAsset asset = makeAsset(testing::cylinderAsset(SkinningMode::kDualQuaternion));
  Result<VulkanRuntime> gpu = VulkanRuntime::create(device(), asset, withCapacity(5));
  Result<CpuRuntime> cpu = CpuRuntime::create(asset, withCapacity(5));
  ASSERT_TRUE(gpu.ok() && cpu.ok()) << gpu.status().toString();
  ASSERT_TRUE(gpu->setInstanceCount(5).ok() && cpu->setInstanceCount(5).ok());
  for (std::uint32_t k = 0; k < 5; ++k) setBoth(*cpu, *gpu, k, InstanceState::atTime(0.7 * k).withPreset(k % 3));
  Result<std::uint64_t> cpu_frame = cpu->submitFrame();
  Result<std::uint64_t> gpu_frame = gpu->submitFrame();
  ASSERT_TRUE(cpu_frame.ok() && gpu_frame.ok());
  expectSameFrame(*cpu, *cpu_frame, *gpu, *gpu_frame, 5, "cylinder dqs");
}

// A runtime moved from (into a container, say) is empty: its calls say so, where its counts once
// sent them through arrays it no longer had.
TEST_F(GpuTest, AMovedFromRuntimeRefusesItsCalls) {
  const RuntimeAsset asset = makeAsset(testing::cylinderAsset());
  Result<VulkanRuntime> gpu = VulkanRuntime::create(device(), asset, withCapacity(2));
  ASSERT_TRUE(gpu.ok()) << gpu.status().toString();
  ASSERT_TRUE(gpu->setInstanceCount(2).ok());
  Result<std::uint64_t> first = gpu->submitFrame();
  ASSERT_TRUE(first.ok()) << first.status().toString();
  VulkanRuntime owner = std::move(*gpu);
  EXPECT_EQ(gpu->instanceCount(), 0u);
  EXPECT_EQ(gpu->capacity(), 0u);
  EXPECT_EQ(gpu->outputVertexCount(), 0u);
  const Result<std::uint64_t> moved_frame = gpu->submitFrame();
  ASSERT_FALSE(moved_frame.ok());
  EXPECT_NE(moved_frame.status().message().find("submitFrame: this runtime was moved from"), std::string::npos)
      << moved_frame.status().message();
  std::vector<InstanceBounds> bounds(2);
  EXPECT_EQ(gpu->readBounds(*first, bounds).code(), StatusCode::kInvalidArgument);
  EXPECT_TRUE(owner.readBounds(*first, bounds).ok());
  EXPECT_TRUE(owner.submitFrame().ok());
}

// Two frames submitted before any wait: each keeps its own inputs and outputs.
TEST_F(GpuTest, RuntimeDoubleBuffersItsFrames) {
  const RuntimeAsset asset = makeAsset(testing::cylinderAsset());
  Result<VulkanRuntime> gpu = VulkanRuntime::create(device(), asset, withCapacity(8));
  Result<CpuRuntime> cpu = CpuRuntime::create(asset, withCapacity(8));
  ASSERT_TRUE(gpu.ok() && cpu.ok());
  ASSERT_TRUE(gpu->setInstanceCount(8).ok() && cpu->setInstanceCount(8).ok());
  std::uint64_t gpu_frames[2], cpu_frames[2];
  for (int f = 0; f < 2; ++f) {
    for (std::uint32_t k = 0; k < 8; ++k) setBoth(*cpu, *gpu, k, InstanceState::atTime(f == 0 ? 0.1 * k : 2.9 - 0.3 * k));
    Result<std::uint64_t> g = gpu->submitFrame();
    Result<std::uint64_t> c = cpu->submitFrame();
    ASSERT_TRUE(g.ok() && c.ok());
    gpu_frames[f] = *g;
    cpu_frames[f] = *c;
  }
  ASSERT_EQ(gpu_frames[1], gpu_frames[0] + 1);
  for (int f = 0; f < 2; ++f) expectSameFrame(*cpu, cpu_frames[f], *gpu, gpu_frames[f], 8, "frame " + std::to_string(f + 1));
  // The frames differ, so keeping both apart is tested.
  EXPECT_GT(worstGap(read(*gpu, gpu_frames[0], 3), read(*gpu, gpu_frames[1], 3)).gap, 1e-3);
  Result<RuntimeFrameBuffers> first = gpu->frameBuffers(gpu_frames[0]);
  Result<RuntimeFrameBuffers> second = gpu->frameBuffers(gpu_frames[1]);
  ASSERT_TRUE(first.ok() && second.ok());
  EXPECT_NE(first->positions, second->positions);
  EXPECT_EQ(first->instance_stride, VkDeviceSize{asset.vertexCount()} * 16);
  Result<RuntimeOutputBarriers> barriers = gpu->outputBarriers(gpu_frames[1]);
  ASSERT_TRUE(barriers.ok());
  EXPECT_EQ(barriers->count, 2u);
  EXPECT_EQ(barriers->barriers[0].buffer, second->positions);
  EXPECT_EQ(barriers->barriers[1].buffer, second->normals);
  EXPECT_EQ(barriers->barriers[0].dstAccessMask, static_cast<VkAccessFlags>(VK_ACCESS_VERTEX_ATTRIBUTE_READ_BIT));
  // A third frame reuses the first one's slot.
  ASSERT_TRUE(gpu->submitFrame().ok());
  EXPECT_EQ(gpu->frameBuffers(gpu_frames[0]).status().code(), StatusCode::kInvalidArgument);
  ASSERT_TRUE(gpu->wait().ok());
}

TEST_F(GpuTest, RuntimeHandlesZeroOneAndManyInstances) {
  const RuntimeAsset asset = makeAsset(testing::cylinderAsset());
  constexpr std::uint32_t kMany = 300;
  RuntimeOptions options = withCapacity(kMany);
  options.frames_in_flight = 3;
  Result<VulkanRuntime> gpu = VulkanRuntime::create(device(), asset, options);
  Result<CpuRuntime> cpu = CpuRuntime::create(asset, options);
  ASSERT_TRUE(gpu.ok() && cpu.ok()) << gpu.status().toString();
  for (std::uint32_t count : {0u, 1u, 37u, kMany}) {
    ASSERT_TRUE(gpu->setInstanceCount(count).ok() && cpu->setInstanceCount(count).ok());
    for (std::uint32_t k = 0; k < count; ++k) setBoth(*cpu, *gpu, k, InstanceState::atTime(3.0 * k / kMany).withPreset(k % 3));
    Result<std::uint64_t> g = gpu->submitFrame();
    Result<std::uint64_t> c = cpu->submitFrame();
    ASSERT_TRUE(g.ok() && c.ok()) << g.status().toString();
    expectSameFrame(*cpu, *c, *gpu, *g, count, std::to_string(count) + " instances");
  }
  std::vector<gpu::Float4> out(asset.vertexCount());
  EXPECT_EQ(gpu->readPositions(gpu->lastFrame(), kMany, out).code(), StatusCode::kInvalidArgument);
}

// The fallback for devices without subgroup arithmetic: the same outputs and boxes.
TEST_F(GpuTest, RuntimeSharedMemoryBoundsMatchToo) {
  const RuntimeAsset asset = makeAsset(testing::cylinderAsset());
  Result<VulkanRuntime> subgroup = VulkanRuntime::create(device(), asset, withCapacity(6));
  Result<VulkanRuntime> shared = VulkanRuntime::create(device(), asset, withCapacity(6), {.allow_subgroups = false});
  Result<CpuRuntime> cpu = CpuRuntime::create(asset, withCapacity(6));
  ASSERT_TRUE(subgroup.ok() && shared.ok() && cpu.ok());
  EXPECT_FALSE(shared->subgroupBounds());
  std::printf("subgroup bounds on %s: %s\n", device().name(), subgroup->subgroupBounds() ? "yes" : "no");
  ASSERT_TRUE(shared->setInstanceCount(6).ok() && cpu->setInstanceCount(6).ok());
  for (std::uint32_t k = 0; k < 6; ++k) setBoth(*cpu, *shared, k, InstanceState::atTime(0.5 * k).withPreset(k % 3));
  Result<std::uint64_t> g = shared->submitFrame();
  Result<std::uint64_t> c = cpu->submitFrame();
  ASSERT_TRUE(g.ok() && c.ok());
  expectSameFrame(*cpu, *c, *shared, *g, 6, "shared-memory bounds");
}

// The discrete-GPU path, forced: boxes reduced in device-local memory and copied into cached host
// memory by every frame's last commands. Four frames through the two slots with changing instance
// counts; expectSameFrame holds each box to the positions of its own frame, so a stale copy fails.
TEST_F(GpuTest, RuntimeStagedBoundsMatchToo) {
  const RuntimeAsset asset = makeAsset(testing::cylinderAsset());
  Result<VulkanRuntime> gpu = VulkanRuntime::create(device(), asset, withCapacity(6), {.bounds = BoundsReadback::kStaged});
  Result<CpuRuntime> cpu = CpuRuntime::create(asset, withCapacity(6));
  Result<VulkanRuntime> plain = VulkanRuntime::create(device(), asset, withCapacity(1));
  ASSERT_TRUE(gpu.ok() && cpu.ok() && plain.ok()) << gpu.status().toString();
  EXPECT_TRUE(gpu->stagedBounds());
  std::printf("bounds on %s: %s\n", device().name(), plain->stagedBounds() ? "copied to cached memory" : "read in place");
  const std::uint32_t counts[] = {3, 6, 4, 5};
  for (std::uint32_t f = 0; f < 4; ++f) {
    const std::uint32_t count = counts[f];
    ASSERT_TRUE(gpu->setInstanceCount(count).ok() && cpu->setInstanceCount(count).ok());
    for (std::uint32_t k = 0; k < count; ++k) {
      setBoth(*cpu, *gpu, k, InstanceState::atTime(0.5 * k + 0.3 * f).withPreset(k % 3));
    }
    Result<std::uint64_t> g = gpu->submitFrame();
    Result<std::uint64_t> c = cpu->submitFrame();
    ASSERT_TRUE(g.ok() && c.ok()) << g.status().toString();
    expectSameFrame(*cpu, *c, *gpu, *g, count, "staged bounds, frame " + std::to_string(f));
  }
}

// memory(): every slot's output buffers at no less than their sizes (allocations round up to the
// device's alignment), the uploaded asset's share independent of the capacity, the folded series
// growing with it, and nothing more after frames.
TEST_F(GpuTest, RuntimeMemoryCountsItsBuffers) {
  const RuntimeAsset asset = makeAsset(testing::cylinderAsset());
  const PackedDeformData& data = asset.packed(0);
  const std::uint64_t v = asset.vertexCount();
  RuntimeOptions options = withCapacity(3);
  Result<VulkanRuntime> small = VulkanRuntime::create(device(), asset, options);
  options.capacity = 7;
  Result<VulkanRuntime> big = VulkanRuntime::create(device(), asset, options);
  ASSERT_TRUE(small.ok() && big.ok()) << small.status().toString();
  const RuntimeMemory a = small->memory();
  const RuntimeMemory b = big->memory();
  std::printf("memory on %s, 3 / 7 instances: asset %llu, inputs %llu / %llu, outputs %llu / %llu bytes, device-local %llu / %llu\n",
              device().name(), static_cast<unsigned long long>(a.asset), static_cast<unsigned long long>(a.inputs),
              static_cast<unsigned long long>(b.inputs), static_cast<unsigned long long>(a.outputs),
              static_cast<unsigned long long>(b.outputs), static_cast<unsigned long long>(a.device_local),
              static_cast<unsigned long long>(b.device_local));
  // Per slot: positions and normals (capacity x V Float4) and the bounds' keys; rounding up adds
  // less than 64 KiB to each of those three buffers.
  auto outputs = [&](std::uint64_t capacity) { return 2 * capacity * (2 * v * sizeof(gpu::Float4) + sizeof(gpu::BoundsKeys)); };
  constexpr std::uint64_t kRounding = std::uint64_t{65536} * 2 * 3;
  EXPECT_GE(a.outputs, outputs(3));
  EXPECT_LT(a.outputs, outputs(3) + kRounding);
  EXPECT_GE(b.outputs, outputs(7));
  EXPECT_LT(b.outputs, outputs(7) + kRounding);
  EXPECT_GE(a.asset, data.rest_positions.size() * sizeof(data.rest_positions[0]) +
                         data.coefficients.size() * sizeof(data.coefficients[0]));
  EXPECT_EQ(a.asset, b.asset);
  // Four more instances' folded series at least.
  EXPECT_GE(b.inputs - a.inputs, 4ull * data.curve_count * gpu::coefficientsPerCurve(data.modes) * sizeof(gpu::Float4));
  EXPECT_LE(a.device_local, a.total());

  ASSERT_TRUE(big->setInstanceCount(7).ok());
  for (int f = 0; f < 3; ++f) ASSERT_TRUE(big->submitFrame().ok());
  ASSERT_TRUE(big->wait().ok());
  const RuntimeMemory after = big->memory();
  EXPECT_EQ(after.total(), b.total());
  EXPECT_EQ(after.device_local, b.device_local);
}

TEST_F(GpuTest, RuntimeWithoutNormals) {
  const RuntimeAsset asset = makeAsset(testing::cylinderAsset());
  RuntimeOptions options = withCapacity(2);
  options.normals = false;
  Result<VulkanRuntime> gpu = VulkanRuntime::create(device(), asset, options);
  Result<CpuRuntime> cpu = CpuRuntime::create(asset, options);
  ASSERT_TRUE(gpu.ok() && cpu.ok());
  ASSERT_TRUE(gpu->setInstanceCount(2).ok() && cpu->setInstanceCount(2).ok());
  setBoth(*cpu, *gpu, 1, InstanceState::atTime(1.5));
  Result<std::uint64_t> g = gpu->submitFrame();
  Result<std::uint64_t> c = cpu->submitFrame();
  ASSERT_TRUE(g.ok() && c.ok());
  expectSameFrame(*cpu, *c, *gpu, *g, 2, "no normals");
  EXPECT_EQ(gpu->frameBuffers(*g)->normals, VK_NULL_HANDLE);
  EXPECT_EQ(gpu->outputBarriers(*g)->count, 1u);
}

// A glTF-like asset's render vertices (runtime_fixtures.hpp's withSeams): render_gather.comp's
// outputs against the CPU runtime's gather, and the frame buffers a renderer binds are those.
TEST_F(GpuTest, RuntimeRenderLayoutMatchesTheCpuRuntime) {
  const RuntimeAsset asset = makeAsset(testing::withSeams(testing::cylinderAsset()));
  for (const bool normals : {true, false}) {
    RuntimeOptions options = withCapacity(5);
    options.render_layout = true;
    options.normals = normals;
    Result<VulkanRuntime> gpu = VulkanRuntime::create(device(), asset, options);
    Result<CpuRuntime> cpu = CpuRuntime::create(asset, options);
    ASSERT_TRUE(gpu.ok() && cpu.ok()) << gpu.status().toString();
    ASSERT_TRUE(gpu->setInstanceCount(5).ok() && cpu->setInstanceCount(5).ok());
    for (std::uint32_t k = 0; k < 5; ++k) setBoth(*cpu, *gpu, k, InstanceState::atTime(0.55 * k).withPreset(k % 3));
    Result<std::uint64_t> g = gpu->submitFrame();
    Result<std::uint64_t> c = cpu->submitFrame();
    ASSERT_TRUE(g.ok() && c.ok()) << g.status().toString();
    expectSameFrame(*cpu, *c, *gpu, *g, 5, normals ? "render layout" : "render layout, no normals");
    Result<RuntimeFrameBuffers> buffers = gpu->frameBuffers(*g);
    Result<RuntimeOutputBarriers> barriers = gpu->outputBarriers(*g);
    ASSERT_TRUE(buffers.ok() && barriers.ok());
    EXPECT_EQ(buffers->instance_stride, VkDeviceSize{asset.renderVertexCount()} * 16);
    EXPECT_EQ(barriers->barriers[0].buffer, buffers->positions);
    EXPECT_EQ(barriers->count, normals ? 2u : 1u);
    if (normals) {
      EXPECT_EQ(barriers->barriers[1].buffer, buffers->normals);
    }
  }
  // The render outputs must fit one storage binding too: a capacity whose topology outputs and
  // folded coefficients fit, but whose render outputs do not.
  const VkDeviceSize range = device().limits().maxStorageBufferRange;
  const std::uint32_t capacity = static_cast<std::uint32_t>(range / (VkDeviceSize{asset.renderVertexCount()} * 16) + 1);
  const PackedDeformData& packed = asset.packed(0);
  const VkDeviceSize folded = VkDeviceSize{capacity} * packed.curve_count * gpu::coefficientsPerCurve(packed.modes) * 16;
  // Such a capacity exists on lavapipe (128 MiB); a device with a larger range hits the dispatch's
  // y extent first, as RuntimeRejectsBadInputNamingTheProblem tests.
  if (VkDeviceSize{capacity} * asset.vertexCount() * 16 > range || folded > range ||
      capacity > device().limits().maxComputeWorkGroupCount[1]) {
    std::printf("render-vertex limit not reachable alone on %s\n", device().name());
    return;
  }
  RuntimeOptions options = withCapacity(capacity);
  options.render_layout = true;
  const Status status = VulkanRuntime::create(device(), asset, options).status();
  EXPECT_EQ(status.code(), StatusCode::kUnavailable);
  EXPECT_NE(status.message().find("one frame's render-vertex positions"), std::string::npos) << status.message();
}

// instance_tangents.comp against the CPU runtime's tangents, on a topology layout and on a render
// layout (where the tangents belong to render vertices), and the buffer a renderer binds.
TEST_F(GpuTest, RuntimeTangentsMatchTheCpuRuntime) {
  for (const bool seamed : {false, true}) {
    const DeformAsset& source = testing::cylinderAsset();
    const RuntimeAsset asset = testing::makeAssetWithTangents(seamed ? testing::withSeams(source) : source);
    RuntimeOptions options = withCapacity(4);
    options.render_layout = seamed;
    options.tangents = true;
    Result<VulkanRuntime> gpu = VulkanRuntime::create(device(), asset, options);
    Result<CpuRuntime> cpu = CpuRuntime::create(asset, options);
    ASSERT_TRUE(gpu.ok() && cpu.ok()) << gpu.status().toString();
    ASSERT_TRUE(gpu->setInstanceCount(4).ok() && cpu->setInstanceCount(4).ok());
    for (std::uint32_t k = 0; k < 4; ++k) setBoth(*cpu, *gpu, k, InstanceState::atTime(0.7 * k + 0.2).withPreset(k % 3));
    Result<std::uint64_t> g = gpu->submitFrame();
    Result<std::uint64_t> c = cpu->submitFrame();
    ASSERT_TRUE(g.ok() && c.ok()) << g.status().toString();
    const std::string what = seamed ? "tangents, render layout" : "tangents";
    expectSameFrame(*cpu, *c, *gpu, *g, 4, what);
    double worst = 0.0;
    for (std::uint32_t k = 0; k < 4; ++k) {
      std::vector<gpu::Float4> expected(cpu->outputVertexCount()), actual(gpu->outputVertexCount());
      ASSERT_TRUE(cpu->readTangents(*c, k, expected).ok());
      const Status read_status = gpu->readTangents(*g, k, actual);
      ASSERT_TRUE(read_status.ok()) << read_status.toString();
      const auto gap = testing::worstGap(expected, actual);
      EXPECT_LT(gap.gap, testing::kNormalTolerance) << what << " instance " << k << ": worst tangent " << gap.vertex;
      worst = std::max(worst, gap.gap);
    }
    std::printf("%s: max |vulkan - cpu| tangents %.2e\n", what.c_str(), worst);
    Result<RuntimeFrameBuffers> buffers = gpu->frameBuffers(*g);
    Result<RuntimeOutputBarriers> barriers = gpu->outputBarriers(*g);
    ASSERT_TRUE(buffers.ok() && barriers.ok());
    EXPECT_NE(buffers->tangents, VK_NULL_HANDLE);
    ASSERT_EQ(barriers->count, 3u);
    EXPECT_EQ(barriers->barriers[2].buffer, buffers->tangents);
  }
}

// Hard edges (render normals): instance_normals.comp over the render vertices against the CPU
// runtime's computeRenderNormals, with tangents made orthogonal to each side's normal.
TEST_F(GpuTest, RuntimeHardEdgesMatchTheCpuRuntime) {
  const DeformAsset source = testing::withSeams(testing::cylinderAsset());
  RuntimeAssetOptions asset_options = testing::presetOptions();
  asset_options.render_normals = testing::hardEdgeNormals(source);
  asset_options.render_tangents = testing::bindTangents(source);
  Result<RuntimeAsset> asset = RuntimeAsset::create(source, asset_options);
  ASSERT_TRUE(asset.ok() && asset->hasHardEdges()) << asset.status().toString();
  for (const bool tangents : {false, true}) {
    RuntimeOptions options = withCapacity(3);
    options.render_layout = true;
    options.tangents = tangents;
    Result<VulkanRuntime> gpu = VulkanRuntime::create(device(), *asset, options);
    Result<CpuRuntime> cpu = CpuRuntime::create(*asset, options);
    ASSERT_TRUE(gpu.ok() && cpu.ok()) << gpu.status().toString();
    ASSERT_TRUE(gpu->setInstanceCount(3).ok() && cpu->setInstanceCount(3).ok());
    for (std::uint32_t k = 0; k < 3; ++k) setBoth(*cpu, *gpu, k, InstanceState::atTime(0.9 * k + 0.4));
    Result<std::uint64_t> g = gpu->submitFrame();
    Result<std::uint64_t> c = cpu->submitFrame();
    ASSERT_TRUE(g.ok() && c.ok()) << g.status().toString();
    expectSameFrame(*cpu, *c, *gpu, *g, 3, tangents ? "hard edges, tangents" : "hard edges");
    if (!tangents) continue;
    double worst = 0.0;
    for (std::uint32_t k = 0; k < 3; ++k) {
      std::vector<gpu::Float4> expected(cpu->outputVertexCount()), actual(gpu->outputVertexCount());
      ASSERT_TRUE(cpu->readTangents(*c, k, expected).ok() && gpu->readTangents(*g, k, actual).ok());
      const auto gap = testing::worstGap(expected, actual);
      EXPECT_LT(gap.gap, testing::kNormalTolerance) << "instance " << k << ": worst tangent " << gap.vertex;
      worst = std::max(worst, gap.gap);
    }
    std::printf("hard edges: max |vulkan - cpu| tangents %.2e\n", worst);
  }
}

TEST_F(GpuTest, RuntimeRejectsBadInputNamingTheProblem) {
  const RuntimeAsset asset = makeAsset(testing::cylinderAsset());
  Result<VulkanRuntime> gpu = VulkanRuntime::create(device(), asset, withCapacity(2));
  ASSERT_TRUE(gpu.ok());
  ASSERT_TRUE(gpu->setInstanceCount(2).ok());
  std::vector<gpu::BoneMatrix> bones(3);
  Status status = gpu->setInstance(0, InstanceState::atTime(0.5).withBones(bones));
  EXPECT_EQ(status.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(status.message().find("instance 0: 3 bone matrices, expected"), std::string::npos) << status.message();
  status = gpu->setInstance(1, InstanceState::atTime(NAN));
  EXPECT_NE(status.message().find("instance 1: time is NaN"), std::string::npos) << status.message();
  status = gpu->setInstance(5, InstanceState::atTime(0.5));
  EXPECT_NE(status.message().find("instance 5 is out of range"), std::string::npos) << status.message();
  EXPECT_EQ(gpu->frameBuffers(1).status().code(), StatusCode::kInvalidArgument);  // nothing submitted yet
  std::vector<InstanceBounds> bounds(2);
  EXPECT_NE(gpu->readBounds(1, bounds).message().find("none submitted yet"), std::string::npos);

  // Limits of the device: more instances than a dispatch's y extent, or outputs beyond one binding.
  const std::uint32_t too_many = device().limits().maxComputeWorkGroupCount[1] + 1u;
  if (too_many != 0) {
    status = VulkanRuntime::create(device(), asset, withCapacity(too_many)).status();
    EXPECT_EQ(status.code(), StatusCode::kUnavailable);
    EXPECT_NE(status.message().find("maxComputeWorkGroupCount[1]"), std::string::npos) << status.message();
  }
  const VkDeviceSize per_instance = VkDeviceSize{asset.vertexCount()} * 16;
  const VkDeviceSize over = device().limits().maxStorageBufferRange / per_instance + 1;
  if (over <= device().limits().maxComputeWorkGroupCount[1]) {
    status = VulkanRuntime::create(device(), asset, withCapacity(static_cast<std::uint32_t>(over))).status();
    EXPECT_EQ(status.code(), StatusCode::kUnavailable);
    EXPECT_NE(status.message().find("maxStorageBufferRange"), std::string::npos) << status.message();
  }
}

}  // namespace
}  // namespace odeskin
