// SPDX-License-Identifier: MIT
// Soak test of CpuRuntime (issue 9, point 4): 100 instances, each at its own time, speed and
// preset (every fourth with engine bones placed in the world), play 10,000 frames. After a warm-up
// the test reads the resident set and the count of operator new calls; at the end neither may have
// grown beyond the bounds below. Every 500th frame (and the last), four instances are compared with
// the double reference (1e-5 of the box's longest side, the fast path's tolerance), and every
// instance's bounds must be exactly the min and max of its positions; every frame's bounds must be
// finite and non-empty. A second run holds one cat on four threads (the path that spreads an
// instance's vertices over the threads) to the same checks for 2,000 frames.
//
// The CI configuration plays the cylinder (420 vertices, 3 segments), so that the run stays well
// under a minute under AddressSanitizer on 2 cores. The long run is the same program:
//   ODESKIN_SOAK_MESH=cat ODESKIN_SOAK_INSTANCES=1000 ODESKIN_SOAK_FRAMES=2000 build/tests/soak_test
// (docs/reliability.md, "Determinism and load" has the measured numbers).
#include <chrono>
#include <cstdio>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "engine/runtime/cpu_runtime.hpp"
#include "runtime/allocation_counter.hpp"
#include "runtime/soak_support.hpp"

namespace odeskin {
namespace {

using testing::SoakClock;
using testing::SoakConfig;

// The resident set may grow by this much after the warm-up: no per-frame array of even the
// cylinder's 100 instances (42,000 vertices, 0.7 MB of positions) could hide below it for long,
// while allocator and thread-stack noise stays under it.
constexpr double kResidentGrowthMiB = 2.0;

// Plays config.frames frames on a CpuRuntime of `threads` threads (0: all), as an engine would.
void soakCpuRuntime(const SoakConfig& config, unsigned threads) {
  const DeformAsset* source = testing::soakAsset(config.mesh);
  ASSERT_NE(source, nullptr);
  Result<RuntimeAsset> asset = RuntimeAsset::create(*source, testing::presetOptions());
  ASSERT_TRUE(asset.ok()) << asset.status().toString();
  RuntimeOptions options;
  options.capacity = config.instances;
  options.threads = threads;
  Result<CpuRuntime> created = CpuRuntime::create(*asset, options);
  ASSERT_TRUE(created.ok()) << created.status().toString();
  CpuRuntime& rt = *created;
  ASSERT_TRUE(rt.setInstanceCount(config.instances).ok());

  const std::size_t v = asset->vertexCount();
  const std::size_t b = asset->boneCount();
  const SoakClock clock{asset->endTime(), asset->presetCount()};
  testing::SoakReference reference(*asset);
  std::vector<gpu::BoneMatrix> engine_bones(std::size_t{config.instances} * b);
  std::vector<InstanceBounds> bounds(config.instances);
  const double box = longestBoxSide(source->rest_positions);
  std::printf("soak: %s (%zu vertices, %zu bones, %u presets), %u instances, %llu frames, check every %llu\n",
              config.mesh.c_str(), v, b, asset->presetCount(), config.instances,
              static_cast<unsigned long long>(config.frames), static_cast<unsigned long long>(config.check_every));

  double worst = 0.0;
  std::uint64_t checks = 0, allocations_in_frames = 0, bytes_in_frames = 0;
  std::size_t resident_start = 0;
  testing::AllocationCount counted_start;
  const auto start = std::chrono::steady_clock::now();
  const double cpu_start = testing::cpuSeconds();
  auto steady = start;
  double check_seconds = 0.0, prepare_seconds = 0.0, deform_seconds = 0.0;
  for (std::uint64_t f = 0; f < config.frames; ++f) {
    if (f == config.warm_up) {
      resident_start = testing::residentBytes();
      counted_start = testing::allocationsSoFar();
      steady = std::chrono::steady_clock::now();
    }
    // What an engine does every frame: set each instance, submit, read the bounds to cull.
    const testing::AllocationCount before = testing::allocationsSoFar();
    const Status set = testing::setInstances(rt, *asset, clock, config.instances, f, engine_bones);
    ASSERT_TRUE(set.ok()) << "frame " << f << ": " << set.toString();
    Result<std::uint64_t> frame = rt.submitFrame();
    ASSERT_TRUE(frame.ok()) << "frame " << f << ": " << frame.status().toString();
    ASSERT_EQ(*frame, f + 1);
    ASSERT_TRUE(rt.readBounds(*frame, bounds).ok());
    const testing::AllocationCount after = testing::allocationsSoFar();
    if (f >= config.warm_up) {
      allocations_in_frames += after.calls - before.calls;
      bytes_in_frames += after.bytes - before.bytes;
      Result<FrameTimes> times = rt.frameTimes(*frame);
      ASSERT_TRUE(times.ok());
      prepare_seconds += times->prepare_seconds;
      deform_seconds += times->deform_seconds;
    }
    for (std::uint32_t k = 0; k < config.instances; ++k) {
      ASSERT_FALSE(bounds[k].empty()) << "frame " << f << " instance " << k;
      ASSERT_TRUE(std::isfinite(bounds[k].min.x + bounds[k].min.y + bounds[k].min.z + bounds[k].max.x +
                                bounds[k].max.y + bounds[k].max.z)) << "frame " << f << " instance " << k;
    }

    if (f % config.check_every != 0 && f + 1 != config.frames) continue;
    const auto check_start = std::chrono::steady_clock::now();
    Result<std::span<const gpu::Float4>> all = rt.positions(*frame);
    ASSERT_TRUE(all.ok());
    for (std::uint32_t k = 0; k < config.instances; ++k) {
      const std::span<const gpu::Float4> mine = all->subspan(k * v, v);
      ASSERT_EQ(testing::boundsMiss(bounds[k], mine), 0.0) << "frame " << f << " instance " << k;
    }
    for (std::uint32_t j = 0; j < config.checked_instances; ++j) {
      const std::uint32_t k = testing::checkedInstance(config, f, j);
      const std::span<const gpu::BoneMatrix> given = testing::givenBones(engine_bones, b, k);
      const double gap = reference.gap(clock.time(k, f), clock.preset(k), given, all->subspan(k * v, v)) / box;
      EXPECT_LT(gap, testing::kSoakRelativeTolerance) << "frame " << f << " instance " << k;
      worst = std::max(worst, gap);
      ++checks;
    }
    check_seconds += testing::secondsSince(check_start);
  }
  const double total = testing::secondsSince(start);
  const double measured = testing::secondsSince(steady);
  const std::size_t resident_end = testing::residentBytes();
  const testing::AllocationCount counted_end = testing::allocationsSoFar();
  const double growth = testing::mib(static_cast<double>(resident_end) - static_cast<double>(resident_start));
  const std::uint64_t measured_frames = config.frames - config.warm_up;
  std::printf("soak: %.1f CPU seconds (all threads) for the frames\n", testing::cpuSeconds() - cpu_start);
  std::printf("soak: %.1f s in all, %.3f ms per frame after warm-up (%.1f s of it in checks), %.1f M instance vertices/s\n",
              total, 1e3 * (measured - check_seconds) / static_cast<double>(measured_frames), check_seconds,
              static_cast<double>(measured_frames) * config.instances * static_cast<double>(v) / (measured - check_seconds) / 1e6);
  std::printf("soak: per frame %.3f ms preparing inputs, %.3f ms deforming with normals and bounds\n",
              1e3 * prepare_seconds / static_cast<double>(measured_frames),
              1e3 * deform_seconds / static_cast<double>(measured_frames));
  std::printf("soak: resident %.2f MiB after %llu warm-up frames, %.2f MiB at the end (growth %+.3f MiB)\n",
              testing::mib(static_cast<double>(resident_start)), static_cast<unsigned long long>(config.warm_up),
              testing::mib(static_cast<double>(resident_end)), growth);
  std::printf("soak: operator new in the %llu frames after warm-up: %llu calls, %llu bytes (whole run since: %llu calls)\n",
              static_cast<unsigned long long>(measured_frames), static_cast<unsigned long long>(allocations_in_frames),
              static_cast<unsigned long long>(bytes_in_frames),
              static_cast<unsigned long long>(counted_end.calls - counted_start.calls));
  std::printf("soak: %llu sampled instances against the reference, max |runtime - reference| / box = %.2e\n",
              static_cast<unsigned long long>(checks), worst);
  ASSERT_NE(resident_start, 0u) << "cannot read /proc/self/statm";
  EXPECT_LT(growth, kResidentGrowthMiB);
  // The runtime's contract (deform_runtime.hpp): no method allocates after create().
  EXPECT_EQ(allocations_in_frames, 0u);
  EXPECT_GE(checks, config.frames / config.check_every * config.checked_instances);
}

TEST(Soak, CpuRuntimeTenThousandFramesOfAHundredInstances) {
  soakCpuRuntime(SoakConfig::fromEnvironment(SoakConfig{}), 0);
}

// One instance on more threads than instances: the path that spreads its vertices over the
// threads (deformation, then normals and bounds in chunks), held to the same contract. The cat
// has two chunks of vertices.
TEST(Soak, CpuRuntimeOneCatSpreadOverFourThreads) {
  SoakConfig config;
  config.mesh = "cat";
  config.instances = 1;
  config.frames = 2000;
  config.check_every = 250;
  config.checked_instances = 1;
  const tbb::global_control four(tbb::global_control::max_allowed_parallelism, 4);  // even on 2 cores
  soakCpuRuntime(config, 4);
}

}  // namespace
}  // namespace odeskin
