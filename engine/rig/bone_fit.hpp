// SPDX-License-Identifier: MIT
// Internal to rig/: the weighted Kabsch core on a covariance matrix, and bone transforms fitted to
// one pose for fixed weights (plain weighted Kabsch per bone, then SSDR bone sweeps), shared by
// fitBoneTransforms and autoRig.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "../core/result.hpp"
#include "../kernels/influences.hpp"
#include "../offline/rigid_transform.hpp"

namespace odeskin {

// Second over first singular value of the covariance below which the points count as collinear:
// exactly collinear data gives ~1e-16, and a bone a few vertices thick still gives > 1e-6.
constexpr double kCollinearRatio = 1e-9;
// A vertex whose weight for a bone is below this fraction of the bone's largest weight is left out
// of that bone's alignment: it moves with other bones, and would only add noise.
constexpr double kRelativeWeightThreshold = 1e-3;
// SSDR sweeps stop after this many rounds or when the squared LBS error falls by less than
// kRefineRelativeGain of itself in one round.
constexpr int kDefaultRefineSweeps = 50;
constexpr double kRefineRelativeGain = 1e-9;

// The rotation and translation maximising tr(R H) for H = sum w (x - c_x)(y - c_y)^T.
// kDegenerate when H has rank < 2 (kCollinearRatio).
Result<RigidTransform> kabschFromCovariance(const Eigen::Matrix3d& h, const Vec3& from_centroid,
                                            const Vec3& to_centroid);

// The influences by bone (columns), with each bone's alignment threshold and a parents-first order.
struct BoneFitProblem {
  std::span<const Vec3> rest;                  // V
  const Influences* influences = nullptr;      // V rows over B bones, validated
  std::vector<std::uint32_t> column_offsets;   // B + 1
  std::vector<std::uint32_t> column_vertices;  // vertices with a positive weight, by bone
  std::vector<double> column_weights;
  std::vector<double> thresholds;              // B: kRelativeWeightThreshold x the bone's largest weight
  std::vector<std::int32_t> parents;           // B, -1 for a root
  std::vector<std::uint32_t> order;            // B: every parent before its children
};

// `parents` must be acyclic and in range (validateRig), `influences` valid for rest.size() rows.
BoneFitProblem makeBoneFitProblem(std::span<const Vec3> rest, const Influences& influences,
                                  std::span<const std::int32_t> parents);

// Per bone, weighted Kabsch of the bind mesh onto `pose` with the bone's weights; a degenerate bone
// takes its parent's transform (identity for a root) and is flagged in `inherited` (B) if given.
std::vector<RigidTransform> initialBoneTransforms(const BoneFitProblem& problem, std::span<const Vec3> pose,
                                                  std::vector<char>* inherited = nullptr);

// SSDR bone sweeps from `transforms` (B): each bone in turn becomes the rigid transform minimising
// the LBS error of `pose` with the other bones fixed. Bones whose alignment is degenerate follow
// their parent. Returns the final sum of squared vertex errors.
double refineBoneTransforms(const BoneFitProblem& problem, std::span<const Vec3> pose,
                            std::vector<RigidTransform>& transforms, int max_sweeps);

}  // namespace odeskin
