// SPDX-License-Identifier: MIT
// Determinism (issue 9, point 4): what is bit-identical across runs and TBB thread counts, and
// what is only within a tolerance.
//  - The fit pipeline (rig, curves, bindings, residual fits; TBB inside) on real data, at 1, 2 and
//    4 threads and twice at 4 (cat, 2 poses; horse, 3 keys at 1 and 4): the .odsk bytes are identical.
//  - The double reference kernel (FourierDeformJob through DeformPlayer): identical frames across
//    runs and thread counts.
//  - The float fast paths (FourierDeformFastJob, CpuDeformKernel on every instruction set this CPU
//    runs, CpuRuntime): identical across runs and thread counts (each vertex, block and instance is
//    computed by one thread in a fixed order, so the split cannot change a result), and within 1e-5
//    of the box's longest side of the double reference (the tolerance of cpu_deform_kernel_test and
//    cpu_runtime_test). The instruction sets differ from one another by float rounding only.
// "4 threads" is forced with tbb::global_control and a tbb::task_arena even on a 2-core machine;
// a probe checks that more than one thread really ran, else the comparison would prove nothing.
#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "engine/io/asset_file.hpp"
#include "engine/kernels/cpu_deform_kernel.hpp"
#include "engine/kernels/fourier_deform_fast_job.hpp"
#include "engine/runtime/cpu_runtime.hpp"
#include "runtime/runtime_fixtures.hpp"

namespace odeskin {
namespace {

constexpr double kFastTolerance = 1e-5;  // x the longest box side, float32 against float64
constexpr int kThreadCounts[] = {1, 2, 4};

// Runs `body` with at most `threads` TBB threads, and with exactly that many slots, so that a
// count above the core count still gets its own workers.
template <typename Body>
void withThreads(int threads, const Body& body) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
  tbb::task_arena arena(threads);
  arena.execute(body);
}

// How many distinct threads run a parallel loop of short sleeps under withThreads(threads).
std::size_t threadsSeen(int threads) {
  std::set<std::thread::id> seen;
  std::mutex mutex;
  withThreads(threads, [&] {
    tbb::parallel_for(0, 128, [&](int) {
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
      const std::lock_guard<std::mutex> lock(mutex);
      seen.insert(std::this_thread::get_id());
    });
  });
  return seen.size();
}

TEST(Determinism, ThreadCountsAreReallyUsed) {
  EXPECT_EQ(threadsSeen(1), 1u);
  EXPECT_GE(threadsSeen(2), 2u);
  // A loaded machine may wake the fourth worker late; more than one thread is what the
  // comparisons need.
  const std::size_t four = threadsSeen(4);
  EXPECT_GE(four, 2u);
  std::printf("threads seen at 4: %zu (hardware %u)\n", four, std::thread::hardware_concurrency());
}

// The .odsk section (four-letter tag) holding byte `offset` of an encoded asset, for messages.
std::string sectionAt(const std::string& bytes, std::size_t offset) {
  std::size_t at = 32;  // the header
  if (offset < at) return "header";
  while (at + 12 <= bytes.size()) {
    std::uint64_t size = 0;
    std::memcpy(&size, bytes.data() + at + 4, sizeof(size));
    if (offset < at + 12 + size) return bytes.substr(at, 4);
    at += 12 + size;
  }
  return "past the sections";
}

std::string firstDifference(const std::string& a, const std::string& b) {
  if (a == b) return "";
  const std::size_t n = std::min(a.size(), b.size());
  std::size_t i = 0;
  while (i < n && a[i] == b[i]) ++i;
  return "sizes " + std::to_string(a.size()) + " and " + std::to_string(b.size()) + ", first difference at byte " +
         std::to_string(i) + " in section " + sectionAt(a, i);
}

struct Fit {
  std::string bytes;
  std::vector<double> key_error;
  std::string rig_summary;
};

Fit fitWith(const std::vector<std::filesystem::path>& paths, int threads) {
  Fit fit;
  withThreads(threads, [&] {
    Result<ExampleSet> examples = readObjSequence(paths);
    ASSERT_TRUE(examples.ok()) << examples.status().toString();
    PipelineOptions options;
    options.material = skinMaterial();
    Result<PipelineResult> result = runFitPipeline(*examples, options);
    ASSERT_TRUE(result.ok()) << result.status().toString();
    Result<std::string> bytes = encodeAsset(result->asset);
    ASSERT_TRUE(bytes.ok()) << bytes.status().toString();
    fit = {std::move(bytes).value(), result->report.key_error, result->rig_summary};
  });
  return fit;
}

// The first fit at one thread against fits at `others` threads.
void expectFitsIdentical(const std::vector<std::filesystem::path>& paths, std::initializer_list<int> others,
                         const char* what) {
  const Fit first = fitWith(paths, 1);
  ASSERT_FALSE(first.bytes.empty()) << what;
  for (int threads : others) {
    const Fit again = fitWith(paths, threads);
    EXPECT_TRUE(first.bytes == again.bytes) << what << " at " << threads << " threads: "
                                            << firstDifference(first.bytes, again.bytes);
    EXPECT_EQ(first.key_error, again.key_error) << what << " at " << threads << " threads";
    EXPECT_EQ(first.rig_summary, again.rig_summary) << what << " at " << threads << " threads";
  }
  std::printf("%s: %zu bytes of .odsk, identical at 1 and %zu other runs\n", what, first.bytes.size(), others.size());
}

TEST(Determinism, FitPipelineCatTwoPosesIsBitIdentical) {
  expectFitsIdentical(testing::catPoses(2), {2, 4, 4}, "cat-00, cat-01 (automatic rig)");
}

// Two segments, so the rate chaining across the join is covered too; 1 against 4 threads only, to
// keep the test short (the cat covers 2 threads and the repeat).
TEST(Determinism, FitPipelineHorseThreeKeysIsBitIdentical) {
  expectFitsIdentical(testing::horseFrames({1, 5, 9}), {4}, "horse 1, 5, 9 (automatic rig)");
}

// Frames of the cylinder (the runtime fixtures' fit, given rig, 3 segments): a few times in every
// segment, the joins and both ends.
struct FrameTime {
  std::uint32_t segment;
  double tau;
};

std::vector<FrameTime> frameTimes(std::uint32_t segments) {
  std::vector<FrameTime> times;
  for (std::uint32_t s = 0; s < segments; ++s) {
    for (double tau : {0.0, 0.13, 0.5, 0.87, 1.0}) times.push_back({s, tau});
  }
  return times;
}

std::vector<Vec3> referenceFrames(const DeformAsset& asset) {
  std::vector<Vec3> all;
  Result<DeformPlayer> player = DeformPlayer::create(asset);
  EXPECT_TRUE(player.ok()) << player.status().toString();
  if (!player.ok()) return all;
  std::vector<Vec3> out(asset.vertexCount());
  for (const FrameTime& t : frameTimes(player->segmentCount())) {
    EXPECT_TRUE(player->play(asset, t.segment, t.tau, out).ok());
    all.insert(all.end(), out.begin(), out.end());
  }
  return all;
}

TEST(Determinism, ReferenceKernelIsBitIdenticalAcrossRunsAndThreads) {
  for (SkinningMode skinning : {SkinningMode::kLinear, SkinningMode::kDualQuaternion}) {
    const DeformAsset& asset = testing::cylinderAsset(skinning);
    std::vector<Vec3> first;
    withThreads(1, [&] { first = referenceFrames(asset); });
    ASSERT_EQ(first.size(), asset.vertexCount() * 5 * asset.segments.size());
    for (int threads : {1, 2, 4}) {
      std::vector<Vec3> again;
      withThreads(threads, [&] { again = referenceFrames(asset); });
      ASSERT_EQ(again.size(), first.size());
      EXPECT_EQ(0, std::memcmp(first.data(), again.data(), first.size() * sizeof(Vec3)))
          << (skinning == SkinningMode::kLinear ? "lbs" : "dqs") << " at " << threads << " threads";
    }
  }
}

// One frame's float inputs and double reference.
struct Frame {
  std::uint32_t segment = 0;
  std::vector<gpu::BoneMatrix> bones;
  std::vector<gpu::ModeBasis> basis;
  std::vector<Vec3> reference;
};

std::vector<Frame> framesOf(const DeformAsset& asset) {
  std::vector<Frame> frames;
  Result<DeformPlayer> player = DeformPlayer::create(asset);
  EXPECT_TRUE(player.ok());
  if (!player.ok()) return frames;
  for (const FrameTime& t : frameTimes(player->segmentCount())) {
    Frame f;
    f.segment = t.segment;
    std::vector<ModeBasisValue> basis(player->basisSize());
    std::vector<BoneTransform> bones(asset.bone_count);
    player->basisAt(t.tau, basis);
    player->bonesAt(asset, t.segment, t.tau, bones);
    f.basis.resize(basis.size());
    f.bones.resize(bones.size());
    toGpuBasis(basis, f.basis);
    toGpuBones(bones, f.bones);
    f.reference.resize(asset.vertexCount());
    EXPECT_TRUE(referenceJob(asset, t.segment, basis, bones, f.reference).run().ok());
    frames.push_back(std::move(f));
  }
  return frames;
}

double worstRelative(const std::vector<Frame>& frames, const std::vector<gpu::Float4>& all, std::size_t v) {
  double worst = 0.0;
  for (std::size_t k = 0; k < frames.size(); ++k) {
    const double box = longestBoxSide(frames[k].reference);
    const auto gap = testing::worstGap(frames[k].reference, std::span(all).subspan(k * v, v));
    worst = std::max(worst, gap.gap / box);
  }
  return worst;
}

bool sameBits(const std::vector<gpu::Float4>& a, const std::vector<gpu::Float4>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(gpu::Float4)) == 0;
}

// Every instruction set at kernel threads 1, 2, 4 and 0 (the caller's arena), under TBB arenas of
// 1, 2 and 4 threads, twice: one result per instruction set, within tolerance of the reference.
TEST(Determinism, CpuKernelIsBitIdenticalPerInstructionSetAndWithinTolerance) {
  for (SkinningMode skinning : {SkinningMode::kLinear, SkinningMode::kDualQuaternion}) {
    const DeformAsset& asset = testing::cylinderAsset(skinning);
    const std::vector<Frame> frames = framesOf(asset);
    Result<PackedDeformData> packed = packDeformAsset(asset);
    ASSERT_TRUE(packed.ok()) << packed.status().toString();
    const std::size_t v = asset.vertexCount();
    auto play = [&](const CpuDeformKernel& kernel, unsigned threads) {
      std::vector<gpu::Float4> all(frames.size() * v, gpu::Float4{7, 7, 7, 7});
      for (std::size_t k = 0; k < frames.size(); ++k) {
        EXPECT_TRUE(kernel.deform(frames[k].segment, frames[k].bones, frames[k].basis,
                                  std::span(all).subspan(k * v, v), threads).ok());
      }
      return all;
    };
    std::vector<std::vector<gpu::Float4>> per_arch;
    for (CpuKernelArch arch : supportedCpuKernelArchs()) {
      const std::string what = std::string(cpuKernelArchName(arch)) + (skinning == SkinningMode::kLinear ? " lbs" : " dqs");
      Result<CpuDeformKernel> kernel = CpuDeformKernel::create(*packed, arch);
      ASSERT_TRUE(kernel.ok()) << kernel.status().toString();
      const std::vector<gpu::Float4> first = play(*kernel, 1);
      for (int arena : kThreadCounts) {
        for (unsigned threads : {1u, 2u, 4u, 0u, 0u}) {
          std::vector<gpu::Float4> again;
          withThreads(arena, [&] { again = play(*kernel, threads); });
          EXPECT_TRUE(sameBits(first, again)) << what << ", kernel threads " << threads << " in an arena of " << arena;
        }
      }
      const double worst = worstRelative(frames, first, v);
      EXPECT_LT(worst, kFastTolerance) << what;
      std::printf("cpu kernel %s: max |kernel - reference| / box = %.2e over %zu frames\n", what.c_str(), worst, frames.size());
      per_arch.push_back(first);
    }
    // Instruction sets are not required to agree bit for bit (FMA contraction and vector widths
    // differ); report how far apart they are.
    for (std::size_t a = 1; a < per_arch.size(); ++a) {
      const auto gap = testing::worstGap(per_arch[0], per_arch[a]);
      std::printf("cpu kernel %s vs %s: max coordinate gap %.2e (%s)\n", cpuKernelArchName(supportedCpuKernelArchs()[0]),
                  cpuKernelArchName(supportedCpuKernelArchs()[a]), gap.gap,
                  sameBits(per_arch[0], per_arch[a]) ? "bit-identical" : "not bit-identical");
    }
  }
}

TEST(Determinism, FastJobIsBitIdenticalAcrossThreadsAndWithinTolerance) {
  const DeformAsset& asset = testing::cylinderAsset();
  const std::vector<Frame> frames = framesOf(asset);
  Result<PackedDeformData> packed = packDeformAsset(asset);
  ASSERT_TRUE(packed.ok());
  const std::size_t v = asset.vertexCount();
  auto play = [&](unsigned threads) {
    std::vector<gpu::Float4> all(frames.size() * v);
    for (std::size_t k = 0; k < frames.size(); ++k) {
      EXPECT_TRUE((FourierDeformFastJob{&*packed, frames[k].segment, frames[k].bones, frames[k].basis,
                                        std::span(all).subspan(k * v, v), threads}).run().ok());
    }
    return all;
  };
  const std::vector<gpu::Float4> first = play(1);
  for (int arena : kThreadCounts) {
    for (unsigned threads : {1u, 2u, 4u, 0u}) {
      std::vector<gpu::Float4> again;
      withThreads(arena, [&] { again = play(threads); });
      EXPECT_TRUE(sameBits(first, again)) << "fast job threads " << threads << " in an arena of " << arena;
    }
  }
  const double worst = worstRelative(frames, first, v);
  EXPECT_LT(worst, kFastTolerance);
  std::printf("fast job: max |fast - reference| / box = %.2e over %zu frames\n", worst, frames.size());
}

// Restores ODESKIN_CPU_KERNEL_ARCH (which caps the instruction set CpuRuntime's kernels pick). The
// environment is changed between runs, while no other thread of the test reads it, hence the NOLINTs.
class ArchCap {
 public:
  explicit ArchCap(const char* arch) {
    if (const char* old = std::getenv("ODESKIN_CPU_KERNEL_ARCH")) old_ = old;
    setenv("ODESKIN_CPU_KERNEL_ARCH", arch, 1);  // NOLINT(concurrency-mt-unsafe)
  }
  ~ArchCap() {
    if (old_) setenv("ODESKIN_CPU_KERNEL_ARCH", old_->c_str(), 1);  // NOLINT(concurrency-mt-unsafe)
    else unsetenv("ODESKIN_CPU_KERNEL_ARCH");                         // NOLINT(concurrency-mt-unsafe)
  }
  ArchCap(const ArchCap&) = delete;
  ArchCap& operator=(const ArchCap&) = delete;

 private:
  std::optional<std::string> old_;
};

struct RuntimeFrame {
  std::vector<gpu::Float4> positions, normals;
  std::vector<InstanceBounds> bounds;
};

// Twelve instances of the cylinder at their own times and presets (every third with bones from
// "the engine", placed in the world), one frame submitted twice, on `threads` runtime threads.
RuntimeFrame runtimeFrame(const RuntimeAsset& asset, unsigned threads, std::uint32_t instances) {
  RuntimeFrame out;
  withThreads(4, [&] {
    RuntimeOptions options;
    options.capacity = instances;
    options.threads = threads;
    Result<CpuRuntime> rt = CpuRuntime::create(asset, options);
    ASSERT_TRUE(rt.ok()) << rt.status().toString();
    ASSERT_TRUE(rt->setInstanceCount(instances).ok());
    std::vector<std::vector<gpu::BoneMatrix>> engine_bones(instances);
    for (std::uint32_t k = 0; k < instances; ++k) {
      const double t = asset.endTime() * (k + 0.5) / instances;
      InstanceState state = InstanceState::atTime(t).withPreset(k % asset.presetCount());
      if (k % 3 == 2) {
        std::vector<gpu::BoneMatrix> bones(asset.boneCount());
        const auto [segment, tau] = asset.locate(t);
        asset.bonesAt(segment, tau, bones);
        engine_bones[k] = testing::placed(bones, 0.3 * k, Vec3(0.5 * k, 0.0, -0.25 * k));
        state = state.withBones(engine_bones[k]);
      }
      ASSERT_TRUE(rt->setInstance(k, state).ok());
    }
    Result<std::uint64_t> first = rt->submitFrame();
    Result<std::uint64_t> second = rt->submitFrame();
    ASSERT_TRUE(first.ok() && second.ok());
    const auto p1 = *rt->positions(*first), p2 = *rt->positions(*second);
    const auto n1 = *rt->normals(*first), n2 = *rt->normals(*second);
    EXPECT_EQ(0, std::memcmp(p1.data(), p2.data(), p1.size_bytes())) << "positions of two frames, same state";
    EXPECT_EQ(0, std::memcmp(n1.data(), n2.data(), n1.size_bytes())) << "normals of two frames, same state";
    out.positions.assign(p2.begin(), p2.end());
    out.normals.assign(n2.begin(), n2.end());
    out.bounds.resize(instances);
    ASSERT_TRUE(rt->readBounds(*second, out.bounds).ok());
  });
  return out;
}

bool sameBounds(const std::vector<InstanceBounds>& a, const std::vector<InstanceBounds>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t k = 0; k < a.size(); ++k) {
    // Bits, not values: -0 and +0 (or two NaNs) must not pass as the same result.
    using Bits = std::array<std::uint32_t, 3>;
    if (std::bit_cast<Bits>(a[k].min) != std::bit_cast<Bits>(b[k].min)) return false;
    if (std::bit_cast<Bits>(a[k].max) != std::bit_cast<Bits>(b[k].max)) return false;
  }
  return true;
}

// CpuRuntime at 1, 2 and 4 threads (and 1 instance, which spreads its vertices instead), for every
// instruction set: positions, normals and bounds bit-identical; positions within tolerance.
TEST(Determinism, CpuRuntimeIsBitIdenticalAcrossThreadsPerInstructionSet) {
  Result<RuntimeAsset> asset = RuntimeAsset::create(testing::cylinderAsset(), testing::presetOptions());
  ASSERT_TRUE(asset.ok()) << asset.status().toString();
  const std::uint32_t instances = 12;
  const double box = longestBoxSide(asset->source().rest_positions);
  for (CpuKernelArch arch : supportedCpuKernelArchs()) {
    const ArchCap cap(cpuKernelArchName(arch));
    const RuntimeFrame first = runtimeFrame(*asset, 1, instances);
    ASSERT_EQ(first.positions.size(), std::size_t{instances} * asset->vertexCount());
    for (unsigned threads : {2u, 4u, 0u}) {
      const RuntimeFrame again = runtimeFrame(*asset, threads, instances);
      EXPECT_TRUE(sameBits(first.positions, again.positions)) << cpuKernelArchName(arch) << " positions, " << threads << " threads";
      EXPECT_TRUE(sameBits(first.normals, again.normals)) << cpuKernelArchName(arch) << " normals, " << threads << " threads";
      EXPECT_TRUE(sameBounds(first.bounds, again.bounds)) << cpuKernelArchName(arch) << " bounds, " << threads << " threads";
    }
    // One instance: its vertices, not the instances, are spread over the threads.
    const RuntimeFrame single1 = runtimeFrame(*asset, 1, 1), single4 = runtimeFrame(*asset, 4, 1);
    EXPECT_TRUE(sameBits(single1.positions, single4.positions)) << cpuKernelArchName(arch) << " one instance";
    EXPECT_TRUE(sameBits(single1.normals, single4.normals)) << cpuKernelArchName(arch) << " one instance's normals";

    double worst = 0.0;
    const std::size_t v = asset->vertexCount();
    for (std::uint32_t k = 0; k < instances; ++k) {
      if (k % 3 == 2) continue;  // engine bones: cpu_runtime_test compares those
      const double t = asset->endTime() * (k + 0.5) / instances;
      const auto [segment, tau] = asset->locate(t);
      const auto expected = testing::referencePositions(*asset, k % asset->presetCount(), segment, tau);
      worst = std::max(worst, testing::worstGap(expected, std::span(first.positions).subspan(k * v, v)).gap / box);
    }
    EXPECT_LT(worst, kFastTolerance) << cpuKernelArchName(arch);
    std::printf("cpu runtime %s: max |runtime - reference| / box = %.2e\n", cpuKernelArchName(arch), worst);
  }
}

}  // namespace
}  // namespace odeskin
