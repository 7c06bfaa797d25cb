// SPDX-License-Identifier: MIT
// Soak test of VulkanRuntime (issue 9, point 4), shorter than the CPU one because lavapipe
// deforms only 0.3 to 1 million vertices a second on a shared 2-core machine: 32 instances of the
// cylinder for 500 frames (frames matter more than instances for leaks: every frame cycles the
// frame ring's fences, command buffers and input slots), double-buffered as an engine drives it
// (submit frame f, then read frame f - 1's bounds). After a warm-up the test reads the resident
// set (lavapipe's "device" memory is this process's memory, so it shows device-side growth too)
// and the count of operator new calls; at the end neither may have grown beyond the bounds below.
// Every 100th frame (and the last), four instances are compared with the double reference (1e-5
// of the box's longest side) and every instance's bounds must be exactly the min and max of its
// positions. It runs twice: frames submitted by the runtime (submitFrame), and frames recorded into
// an engine's command buffers (recordFrame), which the engine submits, waits for with its fences
// and reports finished (frameCompleted) before reading their bounds.
// The same ODESKIN_SOAK_* variables as soak_test set a longer run, e.g.
//   ODESKIN_SOAK_INSTANCES=100 ODESKIN_SOAK_FRAMES=10000 XDG_RUNTIME_DIR=/tmp build/tests/vulkan_soak_test
// Like every GPU test, it skips without a device unless ODESKIN_REQUIRE_GPU=1, and any message
// from the loader (or the validation layer, with ODESKIN_VALIDATION=1) fails it.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <optional>
#include <string>

#include <gtest/gtest.h>

#include "host/gpu_test_support.hpp"
#include "host/runtime/vulkan_runtime.hpp"
#include "runtime/allocation_counter.hpp"
#include "runtime/engine_frames.hpp"
#include "runtime/soak_support.hpp"

namespace odeskin {
namespace {

using testing::SoakClock;
using testing::SoakConfig;

// Allowed growth of the resident set after the warm-up (see soak_test.cpp); the sampled checks'
// staging reads come and go, and the driver's own pools may round up a little.
constexpr double kResidentGrowthMiB = 4.0;

// GpuTest with the validation layer off unless ODESKIN_VALIDATION=1 asks for it: the
// layer allocates with operator new on every call it checks (a few dozen per frame), which would
// hide the runtime's own count. vulkan_runtime_test runs the same runtime under the layer.
class VulkanSoak : public testing::GpuTest {
 protected:
  bool wantsValidation() const override { return false; }
  bool validation() const { return instance_ && instance_->validationEnabled(); }
  // `record`: frames recorded into the engine's command buffers instead of submitted.
  void soak(bool record);
};

TEST_F(VulkanSoak, VulkanRuntimeFiveHundredFramesDoubleBuffered) { soak(false); }

TEST_F(VulkanSoak, VulkanRuntimeFiveHundredFramesRecordedIntoAnEnginesCommandBuffers) { soak(true); }

void VulkanSoak::soak(bool record) {
  SoakConfig defaults;
  defaults.instances = 32;
  defaults.frames = 500;
  defaults.check_every = 100;
  defaults.warm_up = 20;
  const SoakConfig config = SoakConfig::fromEnvironment(defaults);
  const DeformAsset* source = testing::soakAsset(config.mesh);
  ASSERT_NE(source, nullptr);
  Result<RuntimeAsset> asset = RuntimeAsset::create(*source, testing::presetOptions());
  ASSERT_TRUE(asset.ok()) << asset.status().toString();
  RuntimeOptions options;
  options.capacity = config.instances;
  Result<VulkanRuntime> created = VulkanRuntime::create(device(), *asset, options);
  ASSERT_TRUE(created.ok()) << created.status().toString();
  VulkanRuntime& rt = *created;
  ASSERT_TRUE(rt.setInstanceCount(config.instances).ok());

  const std::size_t v = asset->vertexCount();
  const std::size_t b = asset->boneCount();
  const SoakClock clock{asset->endTime(), asset->presetCount()};
  testing::SoakReference reference(*asset);
  // Engine bones per frame slot: setInstance copies them, but keep each frame's for the checks.
  std::vector<gpu::BoneMatrix> engine_bones(std::size_t{config.instances} * b);
  std::vector<InstanceBounds> bounds(config.instances);
  std::vector<gpu::Float4> positions(v);
  const double box = longestBoxSide(source->rest_positions);
  std::printf("vulkan soak: %s (%zu vertices), %u instances, %llu frames %s, check every %llu, device %s\n",
              config.mesh.c_str(), v, config.instances, static_cast<unsigned long long>(config.frames),
              record ? "recorded into an engine's command buffers" : "submitted by the runtime",
              static_cast<unsigned long long>(config.check_every), device().name());
  const std::uint32_t slots = rt.framesInFlight();
  testing::EngineFrames engine(device(), slots);
  // Frame `frame`'s engine slot, whose fence the engine waits for before the runtime hears of it.
  auto completeRecorded = [&](std::uint64_t frame) {
    engine.waitFor(static_cast<std::uint32_t>((frame - 1) % slots));
    return rt.frameCompleted(frame);
  };

  double worst = 0.0, gpu_seconds = 0.0;
  std::uint64_t checks = 0, allocations_in_frames = 0, bytes_in_frames = 0;
  std::size_t resident_start = 0;
  const auto start = std::chrono::steady_clock::now();
  const double cpu_start = testing::cpuSeconds();
  auto steady = start;
  double check_seconds = 0.0;
  for (std::uint64_t f = 0; f < config.frames; ++f) {
    if (f == config.warm_up) {
      resident_start = testing::residentBytes();
      steady = std::chrono::steady_clock::now();
    }
    const bool check = f % config.check_every == 0 || f + 1 == config.frames;
    const testing::AllocationCount before = testing::allocationsSoFar();
    const Status set = testing::setInstances(rt, *asset, clock, config.instances, f, engine_bones);
    ASSERT_TRUE(set.ok()) << "frame " << f << ": " << set.toString();
    // An engine culls with an earlier frame's boxes while this one runs: the previous frame's when
    // the runtime submits; when the engine does, the one its fence for this slot has just waited
    // for, read before this frame takes over its slot.
    auto cull = [&](std::uint64_t culled) {
      ASSERT_TRUE(rt.readBounds(culled, bounds).ok()) << "frame " << culled;
      for (std::uint32_t k = 0; k < config.instances; ++k) {
        ASSERT_FALSE(bounds[k].empty()) << "frame " << culled << " instance " << k;
      }
      Result<FrameTimes> times = rt.frameTimes(culled);
      ASSERT_TRUE(times.ok());
      if (f > config.warm_up) gpu_seconds += times->deform_seconds;
    };
    const std::uint32_t slot = static_cast<std::uint32_t>(f % slots);
    if (record && f >= slots) {
      ASSERT_TRUE(completeRecorded(f + 1 - slots).ok()) << "frame " << f + 1 - slots;
      cull(f + 1 - slots);
      if (HasFatalFailure()) return;
    }
    Result<std::uint64_t> frame = record ? rt.recordFrame(engine.begin(slot)) : rt.submitFrame();
    ASSERT_TRUE(frame.ok()) << "frame " << f << ": " << frame.status().toString();
    ASSERT_EQ(*frame, f + 1);
    if (record) engine.submit(slot);
    if (!record && f > 0) cull(f);
    if (HasFatalFailure()) return;
    const testing::AllocationCount after = testing::allocationsSoFar();
    if (f >= config.warm_up) {
      allocations_in_frames += after.calls - before.calls;
      bytes_in_frames += after.bytes - before.bytes;
    }
    if (!check) continue;

    const auto check_start = std::chrono::steady_clock::now();
    if (record) {
      ASSERT_TRUE(completeRecorded(*frame).ok());
    }
    ASSERT_TRUE(rt.readBounds(*frame, bounds).ok());
    for (std::uint32_t k = 0; k < config.instances; ++k) {
      ASSERT_TRUE(rt.readPositions(*frame, k, positions).ok());
      ASSERT_EQ(testing::boundsMiss(bounds[k], positions), 0.0) << "frame " << f << " instance " << k;
    }
    for (std::uint32_t j = 0; j < config.checked_instances; ++j) {
      const std::uint32_t k = testing::checkedInstance(config, f, j);
      ASSERT_TRUE(rt.readPositions(*frame, k, positions).ok());
      const std::span<const gpu::BoneMatrix> given = testing::givenBones(engine_bones, b, k);
      const double gap = reference.gap(clock.time(k, f), clock.preset(k), given, positions) / box;
      EXPECT_LT(gap, testing::kSoakRelativeTolerance) << "frame " << f << " instance " << k;
      worst = std::max(worst, gap);
      ++checks;
    }
    check_seconds += testing::secondsSince(check_start);
  }
  if (record) {
    for (std::uint64_t frame = rt.lastFrame() - std::min<std::uint64_t>(rt.lastFrame(), slots) + 1; frame <= rt.lastFrame(); ++frame) {
      ASSERT_TRUE(completeRecorded(frame).ok()) << "frame " << frame;
    }
  }
  ASSERT_TRUE(rt.wait().ok());
  const double total = testing::secondsSince(start);
  const double measured = testing::secondsSince(steady) - check_seconds;
  const std::size_t resident_end = testing::residentBytes();
  const double growth = testing::mib(static_cast<double>(resident_end) - static_cast<double>(resident_start));
  const std::uint64_t measured_frames = config.frames - config.warm_up;
  std::printf("vulkan soak: %.1f CPU seconds (all threads, lavapipe's included) for the frames\n",
              testing::cpuSeconds() - cpu_start);
  std::printf("vulkan soak: %.1f s in all, %.2f ms per frame after warm-up (gpu %.2f ms), %.1f s in checks\n", total,
              1e3 * measured / static_cast<double>(measured_frames), 1e3 * gpu_seconds / static_cast<double>(measured_frames - 1),
              check_seconds);
  std::printf("vulkan soak: resident %.2f MiB after %llu warm-up frames, %.2f MiB at the end (growth %+.3f MiB)\n",
              testing::mib(static_cast<double>(resident_start)), static_cast<unsigned long long>(config.warm_up),
              testing::mib(static_cast<double>(resident_end)), growth);
  std::printf("vulkan soak: operator new in the %llu frames after warm-up: %llu calls, %llu bytes\n",
              static_cast<unsigned long long>(measured_frames), static_cast<unsigned long long>(allocations_in_frames),
              static_cast<unsigned long long>(bytes_in_frames));
  std::printf("vulkan soak: %llu sampled instances against the reference, max |runtime - reference| / box = %.2e\n",
              static_cast<unsigned long long>(checks), worst);
  ASSERT_NE(resident_start, 0u) << "cannot read /proc/self/statm";
  EXPECT_LT(growth, kResidentGrowthMiB);
  // The runtime's contract (deform_runtime.hpp): no allocation per frame.
  if (!validation()) {
    EXPECT_EQ(allocations_in_frames, 0u);
  }
  EXPECT_GE(checks, config.frames / config.check_every * config.checked_instances);
}

}  // namespace
}  // namespace odeskin
