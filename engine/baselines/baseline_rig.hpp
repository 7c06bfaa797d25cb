// SPDX-License-Identifier: MIT
// The rig every skinning-based method shares (issue 5: "with the same rig"): the bind mesh, the
// influences, the bones' pivots and parents, and each key pose's bone transforms, taken from the
// fitted DeformAsset so that LBS, DQS, PSD and odeskin see exactly the same skeleton. Also the two
// sources of a frame's skeleton: the keys (interpolated, C1 across keys) and a ground-truth frame
// (per-bone rigid fit with the rig's weights).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "../core/result.hpp"
#include "../core/types.hpp"
#include "../kernels/influences.hpp"
#include "../offline/deform_asset.hpp"
#include "../offline/rigid_transform.hpp"

namespace odeskin {

// How a frame's skeleton is fitted to its surface (the truth protocol, and the keys when the
// evaluation asks for the same fit there).
enum class SkeletonFit : std::uint32_t {
  kLbsOptimal = 0,  // fitBoneTransforms: per-bone Kabsch, then SSDR sweeps minimising the frame's LBS error
  kPerBoneRigid,    // fitRigidBoneTransforms: per-bone weighted Kabsch only, as an animation skeleton
};

class BaselineRig {
 public:
  // Copies the rig of `asset` (its influences are the fit's, with ill-conditioned vertices rebound
  // rigidly; see residual_fit.hpp). Errors: those of validateDeformAsset.
  static Result<BaselineRig> fromAsset(const DeformAsset& asset);

  std::size_t vertexCount() const { return rest_positions_.size(); }
  std::uint32_t boneCount() const { return static_cast<std::uint32_t>(pivots_.size()); }
  std::size_t keyCount() const { return key_poses_.size(); }
  std::uint32_t segmentCount() const { return static_cast<std::uint32_t>(key_poses_.size() - 1); }

  std::span<const Vec3> restPositions() const { return rest_positions_; }
  const Influences& influences() const { return influences_; }
  std::span<const std::int32_t> parents() const { return parents_; }  // B, or empty (no hierarchy)
  std::span<const Vec3> pivots() const { return pivots_; }

  // Bone transforms of key k (B entries into `out`, which must hold at least B).
  void keyBones(std::size_t k, std::span<BoneTransform> out) const;
  // The "keys" protocol: bones at (segment, tau) on each bone's RigidKeyPath (squad rotation,
  // Catmull-Rom pivot; DeformPlayer::bonesAt does the same).
  void keyBones(std::uint32_t segment, double tau, std::span<BoneTransform> out) const;
  // The skeleton of a frame: frame.bones when given (truth protocol), else keyBones(segment, tau)
  // written into `scratch` (resized to B). The caller has checked frame.bones' size.
  std::span<const BoneTransform> frameBones(std::uint32_t segment, double tau, std::span<const BoneTransform> given,
                                            std::vector<BoneTransform>& scratch) const;

  // The "truth" protocol: the skeleton of a ground-truth frame, fitted with the rig's weights by
  // fitBoneTransforms (per-bone weighted Kabsch, then SSDR sweeps that minimise the frame's LBS
  // error). Only the skeleton comes from the frame. Errors: kInvalidArgument for a frame of the
  // wrong size or with non-finite positions, and those of fitBoneTransforms.
  // `fit` kPerBoneRigid: the per-bone rigid fit alone (fitRigidBoneTransforms).
  Result<std::vector<BoneTransform>> fitFrameBones(std::span<const Vec3> frame,
                                                   SkeletonFit fit = SkeletonFit::kLbsOptimal) const;

 private:
  std::vector<Vec3> rest_positions_;
  Influences influences_;
  std::vector<Vec3> pivots_;
  std::vector<std::int32_t> parents_;
  std::vector<std::vector<RigidTransform>> key_poses_;  // K x B
  std::vector<RigidKeyPath> paths_;                     // B
};

}  // namespace odeskin
