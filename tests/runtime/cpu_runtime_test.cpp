// SPDX-License-Identifier: MIT
// CpuRuntime against the double-precision reference (DeformPlayer / FourierDeformJob) on fitted
// assets: instances at different times, segments and material presets, engine-supplied bones
// against interpolated ones, bounds, normals, instance counts 0, 1 and many, held frames, and bad
// input. Tolerance 1e-5 of the bounding box's longest side (float32 against float64).
#include <sys/resource.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <tbb/info.h>

#include "engine/core/thread_count.hpp"
#include "engine/io/asset_file.hpp"
#include "engine/runtime/cpu_runtime.hpp"
#include "engine/sanitized_build.hpp"  // tests/engine
#include "runtime_fixtures.hpp"
#include "scratch_dir.hpp"  // tests/

namespace odeskin {
namespace {

using testing::cylinderAsset;
using testing::makeAsset;
using testing::presetOptions;
using testing::referencePositions;
using testing::worstGap;

constexpr double kRelativeTolerance = 1e-5;

CpuRuntime makeRuntime(const RuntimeAsset& asset, std::uint32_t capacity, unsigned threads = 0) {
  RuntimeOptions options;
  options.capacity = capacity;
  options.threads = threads;
  Result<CpuRuntime> r = CpuRuntime::create(asset, options);
  EXPECT_TRUE(r.ok()) << r.status().toString();
  return std::move(r).value();
}

std::vector<gpu::Float4> positionsOf(DeformRuntime& rt, std::uint64_t frame, std::uint32_t instance) {
  std::vector<gpu::Float4> out(rt.asset().vertexCount());
  const Status status = rt.readPositions(frame, instance, out);
  EXPECT_TRUE(status.ok()) << status.toString();
  return out;
}

void expectStatus(const Status& status, StatusCode code, const std::string& words) {
  EXPECT_EQ(status.code(), code) << status.toString();
  EXPECT_NE(status.message().find(words), std::string::npos) << "message '" << status.message() << "' lacks '" << words << "'";
}

struct Case {
  InstanceState state;
  const char* label;
};

// Instances of the cat on both sides of segment joins, inside segments, at both ends of the clip,
// and with every preset.
TEST(CpuRuntime, CatInstancesMatchTheDoubleReference) {
  const RuntimeAsset asset = makeAsset(testing::catAsset());
  ASSERT_EQ(asset.segmentCount(), 9u);
  std::vector<Case> cases = {
      {InstanceState::atTime(0.0), "t = 0"},
      {InstanceState::atTime(0.37), "t = 0.37"},
      {InstanceState::atSegment(3, 1.0), "segment 3 at tau 1"},
      {InstanceState::atSegment(4, 0.0), "segment 4 at tau 0"},
      {InstanceState::atTime(8.61).withPreset(1), "t = 8.61, static preset"},
      {InstanceState::atTime(9.0).withPreset(2), "t = 9 (the end), springy preset"},
      {InstanceState::atSegment(2, 0.5).withPreset(2), "segment 2 at tau 0.5, springy preset"},
  };
  CpuRuntime rt = makeRuntime(asset, static_cast<std::uint32_t>(cases.size()));
  ASSERT_TRUE(rt.setInstanceCount(static_cast<std::uint32_t>(cases.size())).ok());
  for (std::uint32_t k = 0; k < cases.size(); ++k) ASSERT_TRUE(rt.setInstance(k, cases[k].state).ok()) << cases[k].label;
  Result<std::uint64_t> frame = rt.submitFrame();
  ASSERT_TRUE(frame.ok()) << frame.status().toString();
  const double box = longestBoxSide(asset.source().rest_positions);
  for (std::uint32_t k = 0; k < cases.size(); ++k) {
    const InstanceState& s = cases[k].state;
    const auto [segment, tau] = s.segment_time ? std::pair{s.segment_time->segment, s.segment_time->tau} : asset.locate(s.time);
    const auto expected = referencePositions(asset, s.preset, segment, tau);
    const auto gap = worstGap(expected, positionsOf(rt, *frame, k));
    EXPECT_LT(gap.gap / box, kRelativeTolerance) << cases[k].label << ": worst vertex " << gap.vertex;
    std::printf("%s: max |cpu runtime - reference| / box = %.2e\n", cases[k].label, gap.gap / box);
  }
  // The presets really differ mid-segment (else the preset cases above prove nothing).
  const auto asset_mid = referencePositions(asset, 0, 2, 0.5);
  const auto springy_mid = referencePositions(asset, 2, 2, 0.5);
  double preset_gap = 0.0;
  for (std::size_t i = 0; i < asset_mid.size(); ++i) preset_gap = std::max(preset_gap, glm::length(asset_mid[i] - springy_mid[i]));
  EXPECT_GT(preset_gap / box, 100 * kRelativeTolerance);
}

// Bones the engine hands over: the asset's own interpolated bones give bit-identical output, and a
// world placement of other bones matches the reference played with those very matrices.
TEST(CpuRuntime, EngineBonesMatchInterpolatedOnesAndTheReference) {
  const RuntimeAsset asset = makeAsset(cylinderAsset());
  CpuRuntime rt = makeRuntime(asset, 3);
  ASSERT_TRUE(rt.setInstanceCount(3).ok());
  const double t = 1.3;
  const auto [segment, tau] = asset.locate(t);
  std::vector<gpu::BoneMatrix> bones(asset.boneCount());
  asset.bonesAt(segment, tau, bones);
  std::vector<gpu::BoneMatrix> other(asset.boneCount());
  asset.bonesAt(2, 0.8, other);
  const auto world = testing::placed(other, 0.7, Vec3(3.0, -1.0, 2.0));
  ASSERT_TRUE(rt.setInstance(0, InstanceState::atTime(t)).ok());
  ASSERT_TRUE(rt.setInstance(1, InstanceState::atTime(t).withBones(bones)).ok());
  ASSERT_TRUE(rt.setInstance(2, InstanceState::atTime(t).withBones(world).withPreset(1)).ok());
  Result<std::uint64_t> frame = rt.submitFrame();
  ASSERT_TRUE(frame.ok());
  const auto interpolated = positionsOf(rt, *frame, 0);
  const auto given = positionsOf(rt, *frame, 1);
  EXPECT_EQ(worstGap(interpolated, given).gap, 0.0);
  const double box = longestBoxSide(asset.source().rest_positions);
  const auto gap = worstGap(referencePositions(asset, 1, segment, tau, world), positionsOf(rt, *frame, 2));
  EXPECT_LT(gap.gap / box, kRelativeTolerance) << "worst vertex " << gap.vertex;
  std::vector<InstanceBounds> bounds(3);
  ASSERT_TRUE(rt.readBounds(*frame, bounds).ok());
  EXPECT_GT(bounds[2].min.x, bounds[0].max.x);  // moved 3 units along x, beyond the cylinder
}

TEST(CpuRuntime, DualQuaternionAssetMatchesTheReference) {
  const RuntimeAsset asset = makeAsset(cylinderAsset(SkinningMode::kDualQuaternion));
  ASSERT_EQ(asset.packed().skinning, SkinningMode::kDualQuaternion);
  CpuRuntime rt = makeRuntime(asset, 2);
  ASSERT_TRUE(rt.setInstanceCount(2).ok());
  ASSERT_TRUE(rt.setInstance(0, InstanceState::atTime(0.6)).ok());
  ASSERT_TRUE(rt.setInstance(1, InstanceState::atTime(2.4).withPreset(1)).ok());
  Result<std::uint64_t> frame = rt.submitFrame();
  ASSERT_TRUE(frame.ok());
  const double box = longestBoxSide(asset.source().rest_positions);
  for (std::uint32_t k = 0; k < 2; ++k) {
    const auto [segment, tau] = asset.locate(k == 0 ? 0.6 : 2.4);
    const auto gap = worstGap(referencePositions(asset, k, segment, tau), positionsOf(rt, *frame, k));
    EXPECT_LT(gap.gap / box, kRelativeTolerance) << "instance " << k;
  }
}

TEST(CpuRuntime, BoundsAreTheMinAndMaxOfThePositions) {
  const RuntimeAsset asset = makeAsset(cylinderAsset());
  CpuRuntime rt = makeRuntime(asset, 4);
  ASSERT_TRUE(rt.setInstanceCount(4).ok());
  for (std::uint32_t k = 0; k < 4; ++k) ASSERT_TRUE(rt.setInstance(k, InstanceState::atTime(0.9 * k)).ok());
  Result<std::uint64_t> frame = rt.submitFrame();
  ASSERT_TRUE(frame.ok());
  std::vector<InstanceBounds> bounds(4);
  ASSERT_TRUE(rt.readBounds(*frame, bounds).ok());
  for (std::uint32_t k = 0; k < 4; ++k) {
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (const gpu::Float4& p : positionsOf(rt, *frame, k)) {
      lo = glm::min(lo, glm::vec3(p.x, p.y, p.z));
      hi = glm::max(hi, glm::vec3(p.x, p.y, p.z));
    }
    EXPECT_EQ(bounds[k].min, lo) << "instance " << k;
    EXPECT_EQ(bounds[k].max, hi) << "instance " << k;
  }
  EXPECT_NE(bounds[0].max, bounds[3].max);  // the cylinder bends: the boxes follow it
}

// Area-weighted face normals accumulated per vertex in double, face by face (a scatter, unlike the
// runtime's gather), from the positions the runtime returned.
std::vector<Vec3> doubleNormals(const DeformAsset& asset, std::span<const gpu::Float4> p) {
  std::vector<Vec3> n(p.size(), Vec3(0.0));
  auto at = [&](std::uint32_t i) { return Vec3(p[i].x, p[i].y, p[i].z); };
  for (std::size_t f = 0; f < asset.faces.faceCount(); ++f) {
    const std::uint32_t b = asset.faces.face_offsets[f];
    for (std::uint32_t k = b + 1; k + 1 < asset.faces.face_offsets[f + 1]; ++k) {
      const std::uint32_t i0 = asset.faces.indices[b], i1 = asset.faces.indices[k], i2 = asset.faces.indices[k + 1];
      const Vec3 face = glm::cross(at(i1) - at(i0), at(i2) - at(i0));
      n[i0] += face;
      n[i1] += face;
      n[i2] += face;
    }
  }
  for (Vec3& v : n) v = glm::length(v) > 0.0 ? glm::normalize(v) : Vec3(0.0);
  return n;
}

TEST(CpuRuntime, NormalsMatchADoubleComputation) {
  const RuntimeAsset asset = makeAsset(testing::catAsset());
  CpuRuntime rt = makeRuntime(asset, 2);
  ASSERT_TRUE(rt.setInstanceCount(2).ok());
  ASSERT_TRUE(rt.setInstance(0, InstanceState::atTime(4.5)).ok());
  ASSERT_TRUE(rt.setInstance(1, InstanceState::atTime(7.25).withPreset(2)).ok());
  Result<std::uint64_t> frame = rt.submitFrame();
  ASSERT_TRUE(frame.ok());
  double worst = 0.0;
  for (std::uint32_t k = 0; k < 2; ++k) {
    const auto positions = positionsOf(rt, *frame, k);
    std::vector<gpu::Float4> normals(positions.size());
    ASSERT_TRUE(rt.readNormals(*frame, k, normals).ok());
    const auto expected = doubleNormals(asset.source(), positions);
    for (std::size_t i = 0; i < normals.size(); ++i) {
      const Vec3 got(normals[i].x, normals[i].y, normals[i].z);
      worst = std::max(worst, glm::length(got - expected[i]));
      ASSERT_EQ(normals[i].w, 0.0f);
    }
  }
  // float32 cross products of ~0.02-long edges: a few ulps of 1 relative to the edge.
  EXPECT_LT(worst, 1e-4);
  std::printf("max |cpu normal - double normal| = %.2e\n", worst);
}

TEST(CpuRuntime, InstanceCountsZeroOneAndMany) {
  const RuntimeAsset asset = makeAsset(cylinderAsset());
  CpuRuntime rt = makeRuntime(asset, 64);
  // Zero: a frame with nothing in it.
  Result<std::uint64_t> empty = rt.submitFrame();
  ASSERT_TRUE(empty.ok());
  EXPECT_TRUE(rt.readBounds(*empty, {}).ok());
  std::vector<gpu::Float4> out(asset.vertexCount());
  expectStatus(rt.readPositions(*empty, 0, out), StatusCode::kInvalidArgument, "frame 1 has 0 instances");
  // One, then 64 at spread times: every instance equals the single-instance result at its time.
  CpuRuntime single = makeRuntime(asset, 1);
  ASSERT_TRUE(single.setInstanceCount(1).ok());
  ASSERT_TRUE(rt.setInstanceCount(64).ok());
  for (std::uint32_t k = 0; k < 64; ++k) ASSERT_TRUE(rt.setInstance(k, InstanceState::atTime(3.0 * k / 63.0).withPreset(k % 3)).ok());
  Result<std::uint64_t> many = rt.submitFrame();
  ASSERT_TRUE(many.ok());
  for (std::uint32_t k : {0u, 17u, 63u}) {
    ASSERT_TRUE(single.setInstance(0, InstanceState::atTime(3.0 * k / 63.0).withPreset(k % 3)).ok());
    Result<std::uint64_t> one = single.submitFrame();
    ASSERT_TRUE(one.ok());
    EXPECT_EQ(worstGap(positionsOf(single, *one, 0), positionsOf(rt, *many, k)).gap, 0.0) << "instance " << k;
  }
  std::vector<InstanceBounds> bounds(64);
  ASSERT_TRUE(rt.readBounds(*many, bounds).ok());
  Result<std::span<const gpu::Float4>> all = rt.positions(*many);
  ASSERT_TRUE(all.ok());
  EXPECT_EQ(all->size(), 64u * asset.vertexCount());
}

TEST(CpuRuntime, HeldFramesStayReadable) {
  const RuntimeAsset asset = makeAsset(cylinderAsset());
  CpuRuntime rt = makeRuntime(asset, 1);
  ASSERT_TRUE(rt.setInstanceCount(1).ok());
  ASSERT_TRUE(rt.setInstance(0, InstanceState::atTime(0.2)).ok());
  Result<std::uint64_t> first = rt.submitFrame();
  ASSERT_TRUE(rt.setInstance(0, InstanceState::atTime(2.9)).ok());
  Result<std::uint64_t> second = rt.submitFrame();
  ASSERT_TRUE(first.ok() && second.ok());
  const double box = longestBoxSide(asset.source().rest_positions);
  for (auto [frame, t] : {std::pair{*first, 0.2}, std::pair{*second, 2.9}}) {
    const auto [segment, tau] = asset.locate(t);
    EXPECT_LT(worstGap(referencePositions(asset, 0, segment, tau), positionsOf(rt, frame, 0)).gap / box, kRelativeTolerance);
  }
  ASSERT_TRUE(rt.submitFrame().ok());
  std::vector<gpu::Float4> out(asset.vertexCount());
  expectStatus(rt.readPositions(*first, 0, out), StatusCode::kInvalidArgument, "frame 1 is not held (frames held: 2..3)");
  expectStatus(rt.readPositions(9, 0, out), StatusCode::kInvalidArgument, "frame 9 is not held");
  Result<FrameTimes> times = rt.frameTimes(*second);
  ASSERT_TRUE(times.ok());
  EXPECT_GT(times->deform_seconds, 0.0);
  EXPECT_GE(times->submit_seconds, times->prepare_seconds + times->deform_seconds);
}

TEST(CpuRuntime, RejectsBadInputNamingTheProblem) {
  const RuntimeAsset asset = makeAsset(cylinderAsset());
  CpuRuntime rt = makeRuntime(asset, 2);
  expectStatus(rt.setInstanceCount(3), StatusCode::kInvalidArgument, "instance count 3 exceeds the capacity 2");
  ASSERT_TRUE(rt.setInstanceCount(2).ok());
  expectStatus(rt.setInstance(2, InstanceState::atTime(0.5)), StatusCode::kInvalidArgument, "instance 2 is out of range: the runtime has 2 instances");
  expectStatus(rt.setInstance(0, InstanceState::atTime(NAN)), StatusCode::kInvalidArgument, "instance 0: time is NaN");
  expectStatus(rt.setInstance(1, InstanceState::atTime(INFINITY)), StatusCode::kInvalidArgument, "instance 1: time is inf");
  expectStatus(rt.setInstance(1, InstanceState::atTime(3.5)), StatusCode::kInvalidArgument, "instance 1: time 3.5 is outside [0, 3]");
  // One ulp past the end is printed as itself, not rounded to the end it exceeds.
  expectStatus(rt.setInstance(1, InstanceState::atTime(std::nextafter(3.0, 4.0))), StatusCode::kInvalidArgument,
               "instance 1: time 3.0000000000000004 is outside [0, 3]");
  expectStatus(rt.setInstance(0, InstanceState::atSegment(3, 0.5)), StatusCode::kInvalidArgument, "instance 0: segment 3 is out of range");
  expectStatus(rt.setInstance(0, InstanceState::atSegment(1, NAN)), StatusCode::kInvalidArgument, "instance 0: tau NaN is outside [0, 1]");
  std::vector<gpu::BoneMatrix> bones(asset.boneCount() + 1);
  expectStatus(rt.setInstance(0, InstanceState::atTime(0.5).withBones(bones)), StatusCode::kInvalidArgument,
               "instance 0: " + std::to_string(asset.boneCount() + 1) + " bone matrices, expected " +
                   std::to_string(asset.boneCount()));
  bones.pop_back();
  bones[1].row2.w = NAN;
  expectStatus(rt.setInstance(0, InstanceState::atTime(0.5).withBones(bones)), StatusCode::kInvalidArgument,
               "instance 0: bone matrix 1 has a non-finite entry");
  expectStatus(rt.setInstance(0, InstanceState::atTime(0.5).withPreset(3)), StatusCode::kInvalidArgument, "instance 0: preset 3 is out of range");
  // A rejected call leaves the instance as it was: both still play t = 0.
  Result<std::uint64_t> frame = rt.submitFrame();
  ASSERT_TRUE(frame.ok());
  EXPECT_EQ(worstGap(positionsOf(rt, *frame, 0), positionsOf(rt, *frame, 1)).gap, 0.0);
  std::vector<gpu::Float4> short_out(asset.vertexCount() - 1);
  expectStatus(rt.readPositions(*frame, 0, short_out), StatusCode::kInvalidArgument, "out has 419 entries");
  std::vector<InstanceBounds> bounds(1);
  expectStatus(rt.readBounds(*frame, bounds), StatusCode::kInvalidArgument, "frame 1 has 2 instances");
  RuntimeOptions no_frames;
  no_frames.frames_in_flight = 0;
  expectStatus(CpuRuntime::create(asset, no_frames).status(), StatusCode::kInvalidArgument, "frames_in_flight");
  // UINT32_MAX slots of bookkeeping once threw std::bad_alloc out of create().
  no_frames.frames_in_flight = UINT32_MAX;
  expectStatus(CpuRuntime::create(asset, no_frames).status(), StatusCode::kOutOfRange,
               "runtime: frames_in_flight 4294967295 is above 256");
  // More output than the machine has memory: refused before any buffer is made (Linux would grant
  // it and kill the process while zeroing it).
  RuntimeOptions huge;
  huge.capacity = 1u << 31;
  expectStatus(CpuRuntime::create(asset, huge).status(), StatusCode::kOutOfRange,
               "cpu runtime: the output buffers of 2 frames of 2147483648 instances x 420 vertices need about "
               "53760.0 GiB, more than this machine's ");
  RuntimeOptions no_normals;
  no_normals.normals = false;
  Result<CpuRuntime> plain = CpuRuntime::create(asset, no_normals);
  ASSERT_TRUE(plain.ok());
  ASSERT_TRUE(plain->setInstanceCount(1).ok());
  Result<std::uint64_t> plain_frame = plain->submitFrame();
  ASSERT_TRUE(plain_frame.ok());
  std::vector<gpu::Float4> normals(asset.vertexCount());
  expectStatus(plain->readNormals(*plain_frame, 0, normals), StatusCode::kInvalidArgument, "normals off");
}

// Buffers the machine could hold but this process may not (ulimit -v, a container): std::bad_alloc
// from the allocations became std::terminate; it is a Status now. The limit is the process's
// address space now plus 512 MiB, and the runtime asks for about 2 GiB more.
TEST(CpuRuntime, BuffersBeyondTheProcesssMemoryAreAnError) {
  if (testing::kSanitized) GTEST_SKIP() << "RLIMIT_AS does not work under a sanitizer";
  const RuntimeAsset asset = makeAsset(cylinderAsset());
  RuntimeOptions options;
  const std::size_t per_instance = asset.vertexCount() * sizeof(gpu::Float4) * 2 * options.frames_in_flight;
  options.capacity = static_cast<std::uint32_t>((std::size_t{2} << 30) / per_instance);
  long pages = 0;
  if (std::FILE* statm = std::fopen("/proc/self/statm", "r")) {
    if (std::fscanf(statm, "%ld", &pages) != 1) pages = 0;
    std::fclose(statm);
  }
  ASSERT_GT(pages, 0) << "/proc/self/statm";
  rlimit old{};
  ASSERT_EQ(::getrlimit(RLIMIT_AS, &old), 0);
  rlimit limited = old;
  limited.rlim_cur = static_cast<rlim_t>(pages) * static_cast<rlim_t>(::sysconf(_SC_PAGESIZE)) + (rlim_t{512} << 20);
  ASSERT_EQ(::setrlimit(RLIMIT_AS, &limited), 0);
  Result<CpuRuntime> rt = CpuRuntime::create(asset, options);
  ASSERT_EQ(::setrlimit(RLIMIT_AS, &old), 0);
  ASSERT_FALSE(rt.ok());
  EXPECT_EQ(rt.status().code(), StatusCode::kOutOfRange);
  EXPECT_NE(rt.status().message().find("do not fit in this process's memory"), std::string::npos) << rt.status().message();
}

// A runtime moved from is empty; setInstance on it wrote through an empty array (SEGV).
TEST(CpuRuntime, AMovedFromRuntimeRefusesItsCalls) {
  const RuntimeAsset asset = makeAsset(cylinderAsset());
  RuntimeOptions options;
  options.capacity = 2;
  Result<CpuRuntime> rt = CpuRuntime::create(asset, options);
  ASSERT_TRUE(rt.ok()) << rt.status().toString();
  ASSERT_TRUE(rt->setInstanceCount(2).ok());
  CpuRuntime owner = std::move(*rt);
  EXPECT_EQ(rt->instanceCount(), 0u);
  EXPECT_EQ(rt->capacity(), 0u);
  const Status set = rt->setInstance(1, InstanceState::atTime(0.5));
  EXPECT_EQ(set.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(set.message().find("setInstance: this runtime was moved from"), std::string::npos) << set.message();
  EXPECT_EQ(rt->setInstanceCount(1).code(), StatusCode::kInvalidArgument);
  EXPECT_FALSE(rt->submitFrame().ok());
  // The runtime it went to works, and taking it back by assignment empties the other again.
  ASSERT_TRUE(owner.setInstance(1, InstanceState::atTime(0.5)).ok());
  ASSERT_TRUE(owner.submitFrame().ok());
  *rt = std::move(owner);
  EXPECT_EQ(rt->instanceCount(), 2u);
  EXPECT_TRUE(rt->submitFrame().ok());
  EXPECT_EQ(owner.instanceCount(), 0u);
}

TEST(CpuRuntime, ThreadCountDoesNotChangeTheResult) {
  const RuntimeAsset asset = makeAsset(cylinderAsset());
  CpuRuntime one = makeRuntime(asset, 8, 1);
  CpuRuntime all = makeRuntime(asset, 8, 0);
  for (CpuRuntime* rt : {&one, &all}) {
    ASSERT_TRUE(rt->setInstanceCount(8).ok());
    for (std::uint32_t k = 0; k < 8; ++k) ASSERT_TRUE(rt->setInstance(k, InstanceState::atTime(0.37 * k).withPreset(k % 3)).ok());
  }
  Result<std::uint64_t> a = one.submitFrame();
  Result<std::uint64_t> b = all.submitFrame();
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ(worstGap(*one.positions(*a), *all.positions(*b)).gap, 0.0);
  EXPECT_EQ(worstGap(*one.normals(*a), *all.normals(*b)).gap, 0.0);
}

// memory(): the outputs are exactly every slot's arrays, the asset's share does not depend on the
// capacity, the inputs grow with it, and a frame allocates nothing more.
TEST(CpuRuntime, MemoryCountsWhatTheRuntimeHolds) {
  const RuntimeAsset asset = makeAsset(cylinderAsset());
  const std::uint64_t v = asset.vertexCount();
  for (const bool normals : {true, false}) {
    RuntimeOptions options;
    options.frames_in_flight = 2;
    options.normals = normals;
    options.threads = 1;
    options.capacity = 3;
    Result<CpuRuntime> small = CpuRuntime::create(asset, options);
    options.capacity = 7;
    Result<CpuRuntime> big = CpuRuntime::create(asset, options);
    ASSERT_TRUE(small.ok() && big.ok());
    const RuntimeMemory a = small->memory();
    const RuntimeMemory b = big->memory();
    const std::uint64_t per_instance = v * sizeof(gpu::Float4) * (normals ? 2 : 1) + sizeof(InstanceBounds);
    EXPECT_EQ(a.capacity, 3u);
    EXPECT_EQ(a.outputs, per_instance * 2 * 3) << "normals " << normals;
    EXPECT_EQ(b.outputs, per_instance * 2 * 7) << "normals " << normals;
    // The kernel holds at least every vertex's rest position.
    EXPECT_GT(a.asset, v * 3 * sizeof(float));
    EXPECT_EQ(a.asset, b.asset);
    EXPECT_GT(b.inputs, a.inputs);
    EXPECT_EQ(a.device_local, 0u);
    EXPECT_EQ(a.total(), a.asset + a.inputs + a.outputs);
    EXPECT_DOUBLE_EQ(b.perInstance(), static_cast<double>(b.inputs + b.outputs) / 7.0);

    ASSERT_TRUE(big->setInstanceCount(7).ok());
    ASSERT_TRUE(big->submitFrame().ok());
    ASSERT_TRUE(big->submitFrame().ok());
    const RuntimeMemory after = big->memory();
    EXPECT_EQ(after.asset, b.asset);
    EXPECT_EQ(after.inputs, b.inputs);
    EXPECT_EQ(after.outputs, b.outputs);
  }
}

// On 4 threads, instances left over after whole rounds of one per thread (all of 1, 2 or 3; the
// fifth of 5, the last two of 6) take the other path: each one's vertices spread over the threads,
// normals and bounds in chunks of 4,096 vertices (the cat has two). One thread takes the
// instance-per-thread path throughout. Every output must be the same to the bit.
TEST(CpuRuntime, InstancesSpreadOverThreadsGiveTheSameOutputs) {
  // Four threads even on a 2-core machine: the runtime caps its threads at what TBB allows.
  const tbb::global_control four(tbb::global_control::max_allowed_parallelism, 4);
  const RuntimeAsset asset = makeAsset(testing::catAsset());
  CpuRuntime one = makeRuntime(asset, 6, 1);
  CpuRuntime spread = makeRuntime(asset, 6, 4);
  for (const std::uint32_t count : {1u, 2u, 3u, 5u, 6u}) {
    for (CpuRuntime* rt : {&one, &spread}) {
      ASSERT_TRUE(rt->setInstanceCount(count).ok());
      for (std::uint32_t k = 0; k < count; ++k) ASSERT_TRUE(rt->setInstance(k, InstanceState::atTime(0.8 + 1.3 * k)).ok());
    }
    Result<std::uint64_t> a = one.submitFrame();
    Result<std::uint64_t> b = spread.submitFrame();
    ASSERT_TRUE(a.ok() && b.ok());
    EXPECT_EQ(worstGap(*one.positions(*a), *spread.positions(*b)).gap, 0.0) << count << " instances";
    EXPECT_EQ(worstGap(*one.normals(*a), *spread.normals(*b)).gap, 0.0) << count << " instances";
    std::vector<InstanceBounds> lhs(count), rhs(count);
    ASSERT_TRUE(one.readBounds(*a, lhs).ok() && spread.readBounds(*b, rhs).ok());
    for (std::uint32_t k = 0; k < count; ++k) {
      EXPECT_EQ(lhs[k].min, rhs[k].min) << count << " instances, instance " << k;
      EXPECT_EQ(lhs[k].max, rhs[k].max) << count << " instances, instance " << k;
    }
  }
}

// A thread count above what TBB will run is capped, so reports and the runtime's split of the work
// use the threads that run, and no arena of thousands of empty slots is made.
TEST(WorkerArena, ThreadCountsAreCappedAtWhatTbbRuns) {
  const unsigned machine = static_cast<unsigned>(tbb::info::default_concurrency());
  EXPECT_EQ(allowedThreads(), machine);
  EXPECT_EQ(usableThreads(0), machine);
  EXPECT_EQ(usableThreads(1), 1u);
  EXPECT_EQ(usableThreads(100000), machine);
  EXPECT_EQ(WorkerArena(100000).threads(), machine);
  EXPECT_EQ(WorkerArena(1).threads(), 1u);
  {
    const tbb::global_control six(tbb::global_control::max_allowed_parallelism, 6);
    EXPECT_EQ(usableThreads(0), 6u);
    EXPECT_EQ(usableThreads(5), 5u);
    EXPECT_EQ(usableThreads(100000), 6u);
    EXPECT_EQ(WorkerArena(8).threads(), 6u);
  }
  {
    const tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    EXPECT_EQ(usableThreads(4), 1u);
    EXPECT_EQ(WorkerArena(4).threads(), 1u);
  }
  EXPECT_EQ(allowedThreads(), machine);  // the controls are gone with their scopes
}

TEST(RuntimeAsset, PresetsByNameAndTheirErrors) {
  const DeformAsset& source = cylinderAsset();
  const RuntimeAsset asset = makeAsset(source);
  EXPECT_EQ(asset.presetCount(), 3u);
  EXPECT_EQ(*asset.presetIndex("asset"), 0u);
  EXPECT_EQ(*asset.presetIndex("springy"), 2u);
  expectStatus(asset.presetIndex("rubber").status(), StatusCode::kInvalidArgument, "presets: asset, static, springy");
  EXPECT_EQ(asset.presetName(2), "springy");
  EXPECT_EQ(asset.presetName(3), "");  // past the end: read out of bounds before
  // Presets share every array but the rates.
  EXPECT_EQ(asset.packed(2).coefficients.size(), asset.packed(0).coefficients.size());
  EXPECT_NE(asset.ratesOffset(2), asset.ratesOffset(0));
  RuntimeAssetOptions bad;
  bad.presets = {staticPreset(), staticPreset()};
  expectStatus(RuntimeAsset::create(source, bad).status(), StatusCode::kInvalidArgument, "'static' is used twice");
  bad.presets = {MaterialPreset{"asset", {staticMaterial()}}};
  expectStatus(RuntimeAsset::create(source, bad).status(), StatusCode::kInvalidArgument, "reserved");
  bad.presets = {MaterialPreset{"two", {staticMaterial(), skinMaterial()}}};
  expectStatus(RuntimeAsset::create(source, bad).status(), StatusCode::kInvalidArgument,
               "material preset 'two': 2 materials, expected 1 or the asset's 1");
  bad.presets = {MaterialPreset{"", {staticMaterial()}}};
  expectStatus(RuntimeAsset::create(source, bad).status(), StatusCode::kInvalidArgument, "empty name");
  DeformAsset keyless = source;
  keyless.segments.clear();
  keyless.key_poses.resize(1);
  EXPECT_FALSE(RuntimeAsset::create(keyless).ok());
}

TEST(RuntimeAsset, LoadsAnOdskFile) {
  const std::filesystem::path dir = odeskin::testing::scratchDir("runtime_asset");
  const std::filesystem::path path = dir / "cylinder.odsk";
  ASSERT_TRUE(saveAsset(path, cylinderAsset()).ok());
  Result<RuntimeAsset> loaded = RuntimeAsset::load(path, presetOptions());
  ASSERT_TRUE(loaded.ok()) << loaded.status().toString();
  const RuntimeAsset made = makeAsset(cylinderAsset());
  EXPECT_EQ(loaded->vertexCount(), made.vertexCount());
  EXPECT_EQ(worstGap(loaded->packed(2).rates, made.packed(2).rates).gap, 0.0);
  expectStatus(RuntimeAsset::load(dir / "absent.odsk").status(), StatusCode::kIoError, "absent.odsk");
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace odeskin
