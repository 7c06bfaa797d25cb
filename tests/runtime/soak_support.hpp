// SPDX-License-Identifier: MIT
// Shared by the soak tests (soak_test.cpp on the CPU backend, vulkan_soak_test.cpp on Vulkan):
// the configuration (environment variables, so the long run is the same program), each
// instance's clock, an allocation-free double-precision reference, the resident set size, and the
// checks of a sampled frame (positions against the reference, bounds against the positions).
#pragma once

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/core/status.hpp"
#include "engine/kernels/packed_deform.hpp"
#include "engine/runtime/deform_runtime.hpp"
#include "runtime_fixtures.hpp"

namespace odeskin::testing {

// Environment: ODESKIN_SOAK_MESH=cylinder|cat, ODESKIN_SOAK_INSTANCES, ODESKIN_SOAK_FRAMES,
// ODESKIN_SOAK_CHECK_EVERY (frames between sampled checks). Defaults are the CI configuration.
struct SoakConfig {
  std::string mesh = "cylinder";
  std::uint32_t instances = 100;
  std::uint64_t frames = 10000;
  std::uint64_t check_every = 500;
  std::uint64_t warm_up = 100;       // frames before the first memory reading
  std::uint32_t checked_instances = 4;  // instances compared with the reference per sampled frame

  static std::uint64_t number(const char* name, std::uint64_t fallback) {
    const char* value = std::getenv(name);
    if (value == nullptr || *value == '\0') return fallback;
    char* end = nullptr;
    const unsigned long long n = std::strtoull(value, &end, 10);
    if (end == value || *end != '\0' || n == 0) {
      ADD_FAILURE() << name << "=" << value << " is not a positive integer; using " << fallback;
      return fallback;
    }
    return n;
  }

  static SoakConfig fromEnvironment(const SoakConfig& defaults) {
    SoakConfig c = defaults;
    if (const char* mesh = std::getenv("ODESKIN_SOAK_MESH"); mesh != nullptr && *mesh != '\0') c.mesh = mesh;
    c.instances = static_cast<std::uint32_t>(number("ODESKIN_SOAK_INSTANCES", c.instances));
    c.frames = number("ODESKIN_SOAK_FRAMES", c.frames);
    c.check_every = number("ODESKIN_SOAK_CHECK_EVERY", c.check_every);
    c.warm_up = std::min(c.warm_up, c.frames / 10);
    c.checked_instances = std::min(c.checked_instances, c.instances);
    return c;
  }
};

inline const DeformAsset* soakAsset(const std::string& mesh) {
  if (mesh == "cylinder") return &cylinderAsset();
  if (mesh == "cat") return &catAsset();
  ADD_FAILURE() << "ODESKIN_SOAK_MESH=" << mesh << ": expected cylinder or cat";
  return nullptr;
}

// Resident set size of this process (/proc/self/statm), in bytes; 0 where it cannot be read.
inline std::size_t residentBytes() {
  std::ifstream statm("/proc/self/statm");
  std::size_t pages = 0, resident = 0;
  if (!(statm >> pages >> resident)) return 0;
  return resident * static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
}

// Instance k plays the clip at its own speed and phase, there and back (so its motion stays
// continuous), with preset k % presets, and every fourth instance gets its bones from "the
// engine": the asset's own bones moved to a place of its own in the world.
struct SoakClock {
  double end_time = 1.0;
  std::uint32_t presets = 1;
  static constexpr double kFrameSeconds = 1.0 / 60.0;

  double time(std::uint32_t k, std::uint64_t frame) const {
    const double speed = 0.5 + 0.25 * static_cast<double>(k % 7);  // key units per second
    const double phase = 0.37 * static_cast<double>(k);
    const double u = std::fmod(phase + speed * kFrameSeconds * static_cast<double>(frame), 2.0 * end_time);
    return u <= end_time ? u : 2.0 * end_time - u;
  }
  std::uint32_t preset(std::uint32_t k) const { return k % presets; }
  static bool engineBones(std::uint32_t k) { return k % 4 == 3; }
  static Vec3 place(std::uint32_t k) {
    const std::uint32_t row = k / 10;  // rows of 10 instances
    return Vec3(1.5 * (k % 10), 0.0, 1.5 * row);
  }
};

// The asset's interpolated bones at `t`, translated to `offset` (no allocation).
inline void placedBones(const RuntimeAsset& asset, double t, const Vec3& offset, std::span<gpu::BoneMatrix> out) {
  const auto [segment, tau] = asset.locate(t);
  asset.bonesAt(segment, tau, out);
  for (gpu::BoneMatrix& m : out) {
    m.row0.w += static_cast<float>(offset.x);
    m.row1.w += static_cast<float>(offset.y);
    m.row2.w += static_cast<float>(offset.z);
  }
}

// Frame `frame`'s state of every instance, set as an engine sets it each frame; the engine-bone
// instances' palettes are written into `engine_bones` (instances x B, instance k's at k * B). No
// allocation.
inline Status setInstances(DeformRuntime& rt, const RuntimeAsset& asset, const SoakClock& clock,
                           std::uint32_t instances, std::uint64_t frame, std::span<gpu::BoneMatrix> engine_bones) {
  const std::size_t b = asset.boneCount();
  for (std::uint32_t k = 0; k < instances; ++k) {
    const double t = clock.time(k, frame);
    InstanceState state = InstanceState::atTime(t).withPreset(clock.preset(k));
    if (SoakClock::engineBones(k)) {
      std::span<gpu::BoneMatrix> own = engine_bones.subspan(k * b, b);
      placedBones(asset, t, SoakClock::place(k), own);
      state = state.withBones(own);
    }
    ODESKIN_TRY(rt.setInstance(k, state));
  }
  return okStatus();
}

// The bones instance k was given by "the engine", or none when it plays the asset's own.
inline std::span<const gpu::BoneMatrix> givenBones(std::span<const gpu::BoneMatrix> engine_bones, std::size_t b,
                                                   std::uint32_t k) {
  return SoakClock::engineBones(k) ? engine_bones.subspan(k * b, b) : std::span<const gpu::BoneMatrix>();
}

// The instance the j-th check of frame f compares: a different handful each time, engine-bone
// instances among them.
inline std::uint32_t checkedInstance(const SoakConfig& config, std::uint64_t f, std::uint32_t j) {
  return static_cast<std::uint32_t>((f / config.check_every * 13 + std::uint64_t{j} * 29 + std::uint64_t{j} * 3) % config.instances);
}

// The double-precision reference (DeformPlayer time bases, FourierDeformJob) of every preset,
// with its buffers made once, so the sampled checks allocate (almost) nothing mid-run.
class SoakReference {
 public:
  explicit SoakReference(const RuntimeAsset& asset) : asset_(asset) {
    variants_.reserve(asset.presetCount());
    for (std::uint32_t p = 0; p < asset.presetCount(); ++p) {
      if (p == 0) {
        variants_.push_back(asset.source());
      } else {
        Result<DeformAsset> made = assetWithPreset(asset.source(), presetOptions().presets[p - 1]);
        EXPECT_TRUE(made.ok()) << made.status().toString();
        variants_.push_back(made.ok() ? std::move(made).value() : asset.source());
      }
      Result<DeformPlayer> player = DeformPlayer::create(variants_.back());
      EXPECT_TRUE(player.ok()) << player.status().toString();
      if (player.ok()) players_.push_back(std::move(player).value());
    }
    if (!players_.empty()) basis_.resize(players_[0].basisSize());
    bones_.resize(asset.boneCount());
    out_.resize(asset.vertexCount());
  }

  // Instance positions against the reference at global time t with `preset`, and `engine_bones`
  // (float matrices, as the runtime got them) or the key paths in double when empty. Max |gap|.
  double gap(double t, std::uint32_t preset, std::span<const gpu::BoneMatrix> engine_bones,
             std::span<const gpu::Float4> positions) {
    if (players_.size() != asset_.presetCount()) return std::numeric_limits<double>::infinity();
    const DeformAsset& played = variants_[preset];
    const DeformPlayer& player = players_[preset];
    const auto [segment, tau] = player.locate(t);
    player.basisAt(tau, basis_);
    if (engine_bones.empty()) {
      player.bonesAt(played, segment, tau, bones_);
    } else {
      for (std::size_t b = 0; b < bones_.size(); ++b) bones_[b] = fromGpuBone(engine_bones[b]);
    }
    const Status status = referenceJob(played, segment, basis_, bones_, out_).run();
    EXPECT_TRUE(status.ok()) << status.toString();
    return worstGap(out_, positions).gap;
  }

 private:
  const RuntimeAsset& asset_;
  std::vector<DeformAsset> variants_;
  std::vector<DeformPlayer> players_;
  std::vector<ModeBasisValue> basis_;
  std::vector<BoneTransform> bones_;
  std::vector<Vec3> out_;
};

// How far a box misses its positions: 0 when it holds every one and each face touches one (the
// box is exactly their min and max); otherwise the largest miss, or infinity for an empty box.
inline double boundsMiss(const InstanceBounds& box, std::span<const gpu::Float4> positions) {
  if (box.empty()) return std::numeric_limits<double>::infinity();
  glm::vec3 lo(std::numeric_limits<float>::infinity()), hi(-std::numeric_limits<float>::infinity());
  for (const gpu::Float4& p : positions) {
    lo = glm::min(lo, glm::vec3(p.x, p.y, p.z));
    hi = glm::max(hi, glm::vec3(p.x, p.y, p.z));
  }
  const glm::vec3 under = glm::abs(lo - box.min), over = glm::abs(hi - box.max);
  return std::max({under.x, under.y, under.z, over.x, over.y, over.z});
}

// CPU seconds of this process so far, every thread, user and system: on a shared machine the wall
// time says more about the neighbours than about the test.
inline double cpuSeconds() {
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) != 0) return 0.0;
  const auto seconds = [](const timeval& t) { return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec); };
  return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

inline double mib(double bytes) { return bytes / (1024.0 * 1024.0); }

inline double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Sampled instances may differ from the double reference by this much of the box (the fast path's
// tolerance).
constexpr double kSoakRelativeTolerance = 1e-5;

}  // namespace odeskin::testing
