// SPDX-License-Identifier: MIT
#include "deform_player.hpp"

#include <algorithm>
#include <cmath>

namespace odeskin {

Result<DeformPlayer> DeformPlayer::create(const DeformAsset& asset) {
  ODESKIN_TRY(validateDeformAsset(asset));
  DeformPlayer player;
  player.modes_ = asset.modes;
  player.segment_count_ = static_cast<std::uint32_t>(asset.segments.size());
  player.bases_.reserve(asset.materials.size() * static_cast<std::size_t>(asset.modes + 1));
  for (std::size_t m = 0; m < asset.materials.size(); ++m) {
    for (int n = 0; n <= asset.modes; ++n) {
      Result<ModeTimeBasis> basis = ModeTimeBasis::create(asset.materials[m], n);
      if (!basis.ok()) {
        return Status(basis.status().code(), "material " + std::to_string(m) + ": " + basis.status().message());
      }
      player.bases_.push_back(*basis);
    }
  }
  player.bone_paths_ = boneKeyPaths(asset);
  return player;
}

std::vector<RigidKeyPath> boneKeyPaths(const DeformAsset& asset) {
  std::vector<RigidKeyPath> paths;
  std::vector<RigidTransform> keys(asset.key_poses.size());
  paths.reserve(asset.bone_count);
  for (std::uint32_t b = 0; b < asset.bone_count; ++b) {
    for (std::size_t k = 0; k < keys.size(); ++k) keys[k] = asset.key_poses[k][b];
    paths.emplace_back(keys, asset.bone_pivots[b]);
  }
  return paths;
}

std::pair<std::uint32_t, double> DeformPlayer::locate(double t) const {
  const double end = static_cast<double>(segment_count_);
  const double clamped = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, end);
  const std::uint32_t segment = std::min(static_cast<std::uint32_t>(clamped), segment_count_ - 1);
  return {segment, clamped - segment};
}

double remainderWeight(double tau) {
  const double t = std::clamp(tau, 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

void DeformPlayer::basisAt(double tau, std::span<ModeBasisValue> out) const {
  for (std::size_t k = 0; k < bases_.size() && k < out.size(); ++k) {
    const TimeBasisSample s = bases_[k].at(tau);
    out[k] = ModeBasisValue{s.gamma, s.psi};
  }
  if (out.size() > bases_.size()) out[bases_.size()] = ModeBasisValue{remainderWeight(tau), 0.0};
}

void DeformPlayer::bonesAt(const DeformAsset& asset, std::uint32_t segment, double tau,
                           std::span<BoneTransform> out) const {
  for (std::uint32_t b = 0; b < asset.bone_count && b < out.size() && b < bone_paths_.size(); ++b) {
    out[b] = bone_paths_[b].at(segment, tau).matrix();
  }
}

Status DeformPlayer::play(const DeformAsset& asset, std::uint32_t segment, double tau, std::span<Vec3> out) const {
  std::vector<ModeBasisValue> basis(basisSize());
  std::vector<BoneTransform> bones(asset.bone_count);
  basisAt(tau, basis);
  bonesAt(asset, segment, tau, bones);
  return referenceJob(asset, segment, basis, bones, out).run();
}

FourierDeformJob referenceJob(const DeformAsset& asset, std::uint32_t segment, std::span<const ModeBasisValue> basis,
                              std::span<const BoneTransform> bones, std::span<Vec3> out_positions) {
  const DeformSegment& seg = asset.segments[segment];
  FourierDeformJob job;
  job.modes = asset.modes;
  job.residual_space = asset.residual_space;
  job.skinning = asset.skinning;
  job.rest_positions = asset.rest_positions;
  job.bindings = asset.bindings;
  job.base_residuals = seg.base_residuals;
  job.remainder_indices = seg.remainder_indices;
  job.remainders = seg.remainders;
  job.curve_materials = asset.curve_materials;
  job.coefficients = seg.coefficients;
  job.rates = seg.rates;
  job.basis = basis;
  job.influences = InfluencesView(asset.influences);
  job.bones = bones;
  job.out_positions = out_positions;
  return job;
}

}  // namespace odeskin
