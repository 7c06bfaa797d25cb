// SPDX-License-Identifier: MIT
// Per-frame inputs of a DeformAsset: the time basis of every (material, mode) at tau (float64 on
// the host, MATH.md 1.6 and 5.8) and the bone transforms interpolated between the segment's keys.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "../core/result.hpp"
#include "../kernels/fourier_deform_job.hpp"
#include "deform_asset.hpp"
#include "time_basis.hpp"

namespace odeskin {

// Weight of the sparse remainders at tau: 3 tau^2 - 2 tau^3 (0 -> 1 with zero rate at both ends).
double remainderWeight(double tau);

class DeformPlayer {
 public:
  // Sets up every (material, mode) time basis; fails on degenerate or resonant modes, naming them.
  static Result<DeformPlayer> create(const DeformAsset& asset);

  // material_count * (N+1) + 1: every (material, mode), then the remainder weight (gpu_layout.h).
  std::size_t basisSize() const { return bases_.size() + 1; }
  std::uint32_t segmentCount() const { return segment_count_; }

  // Global time t in [0, K-1] -> (segment, tau in [0, 1]); t is clamped to that range.
  std::pair<std::uint32_t, double> locate(double t) const;

  // Time basis values at tau (basisSize() entries); the last one's gamma is remainderWeight(tau).
  void basisAt(double tau, std::span<ModeBasisValue> out) const;
  // Bone transforms of `segment` at tau (asset.bone_count entries), C1 across keys (RigidKeyPath).
  void bonesAt(const DeformAsset& asset, std::uint32_t segment, double tau, std::span<BoneTransform> out) const;
  // One frame of `asset` (the asset this player was made for) on the reference kernel: its V
  // vertices at (segment, tau) into `out`. Loops that play many frames may keep their own buffers
  // and call basisAt, bonesAt and referenceJob instead.
  Status play(const DeformAsset& asset, std::uint32_t segment, double tau, std::span<Vec3> out) const;

  const ModeTimeBasis& basis(std::uint32_t material, int n) const { return bases_[material * (modes_ + 1) + n]; }

 private:
  int modes_ = 0;
  std::uint32_t segment_count_ = 0;
  std::vector<ModeTimeBasis> bases_;
  std::vector<RigidKeyPath> bone_paths_;  // B
};

// The C1 bone path of every bone through the asset's key poses (asset.bone_count entries).
std::vector<RigidKeyPath> boneKeyPaths(const DeformAsset& asset);

// The reference job of `asset` for one frame (spans into asset and the caller's frame buffers).
FourierDeformJob referenceJob(const DeformAsset& asset, std::uint32_t segment, std::span<const ModeBasisValue> basis,
                              std::span<const BoneTransform> bones, std::span<Vec3> out_positions);

}  // namespace odeskin
