// SPDX-License-Identifier: MIT
// Pose-space deformation (Lewis, Cordner, Fong 2000) on top of LBS or DQS, with the key poses as
// the pose-space examples:
//   key k's bind-space corrective  r_i^k = A_i^k^-1 (P_{k,i} - T_i^k(X_i))   (PIPELINE.md 2),
//   where x -> A_i^k x + t_i^k is vertex i's skinning map at key k: the LBS blend (A = sum_b w_ib R_b)
//   or the vertex's blended rigid transform under DQS (A its rotation),
//   frame:  out_i = T_i(X_i + sum_k a_k(q) r_i^k),  a_k = RBF cardinal weights (pose_space_rbf.hpp),
// so every key pose is reproduced exactly when its own skeleton is given. The pose-space
// coordinate q of a skeleton is, per bone, the rotation vector (log map, radians) of its rotation
// relative to bind, taken relative to the parent bone when the rig has a hierarchy (joint angles,
// so a turn of the whole body does not read as a new pose), optionally scaled by sqrt of the bone's
// share of all skinning weight so bones that move many vertices dominate the distance.
#pragma once

#include <span>
#include <vector>

#include "../core/result.hpp"
#include "baseline.hpp"
#include "baseline_rig.hpp"
#include "pose_space_rbf.hpp"

namespace odeskin {

struct PsdOptions {
  RbfOptions rbf;
  bool weight_bones_by_influence = true;
  bool relative_to_parent = true;  // ignored when the rig has no hierarchy
};

// Pose-space coordinate of a skeleton (3 x B values into `out`): the rotation vector of each bone's
// rotation (nearest rotation of its 3x3) relative to bind, or to its parent's rotation when
// `parents` is non-empty, times bone_scales[b] (empty: 1).
void poseSpaceCoordinates(std::span<const BoneTransform> bones, std::span<const std::int32_t> parents,
                          std::span<const double> bone_scales, std::span<double> out);

class PoseSpaceDeformation final : public Baseline {
 public:
  // `keys`: the K example poses the rig's key transforms belong to (K x V). mode: kLinear
  // ("psd_lbs") or kDualQuaternion ("psd_dqs"). Errors: kInvalidArgument (key count or sizes
  // disagree with the rig, non-finite positions), kIllPosed (a vertex's skinning map at a key is
  // singular, naming vertex and key; the rig's conditioned influences prevent it for LBS), and
  // those of RbfInterpolator::create.
  static Result<PoseSpaceDeformation> create(BaselineRig rig, const std::vector<std::vector<Vec3>>& keys,
                                             SkinningMode mode, const PsdOptions& options = {});

  BaselineMethod method() const override;
  Status evaluate(const BaselineFrameInput& frame, std::span<Vec3> out) override;

  // The cardinal weights the frame's skeleton gets (K values), as evaluate uses them.
  void exampleWeights(std::span<const BoneTransform> bones, std::span<double> out) const;
  const RbfInterpolator& interpolator() const { return rbf_; }
  std::span<const Vec3> corrective(std::size_t k) const { return correctives_[k]; }

 private:
  PoseSpaceDeformation(BaselineRig rig, SkinningMode mode, RbfInterpolator rbf);

  BaselineRig rig_;
  SkinningMode mode_;
  RbfInterpolator rbf_;
  std::vector<std::int32_t> parents_;        // B, or empty (global rotations)
  std::vector<double> bone_scales_;          // B, or empty
  std::vector<std::vector<Vec3>> correctives_;  // K x V
  std::vector<BoneTransform> bones_;         // keys protocol scratch
  std::vector<Vec3> corrected_;              // V scratch: X + sum_k a_k r^k
  std::vector<double> query_, weights_;      // 3B and K scratch
};

}  // namespace odeskin
