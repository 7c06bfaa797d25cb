// SPDX-License-Identifier: MIT
// How close a derived skeleton is to a ground-truth one (issue 8 point 3): joint positions
// relative to the mesh's bounding-box diagonal, both ways, and the bone counts. Joints are the
// distinct bone ends (heads and tails, merged within 1e-9 of the diagonal).
#pragma once

#include <vector>

#include "rig.hpp"

namespace odeskin {

struct SkeletonComparison {
  std::size_t truth_bones = 0;
  std::size_t bones = 0;
  std::size_t truth_joints = 0;
  std::size_t joints = 0;
  // Each truth joint to the nearest derived joint (is every true joint found?), / diagonal.
  double truth_to_ours_mean = 0.0;
  double truth_to_ours_max = 0.0;
  // Each derived joint to the nearest truth joint (are there joints where the truth has none?).
  double ours_to_truth_mean = 0.0;
  double ours_to_truth_max = 0.0;
};

// Distinct joints of a skeleton (heads and tails).
std::vector<Vec3> skeletonJoints(const Skeleton& skeleton, double merge_distance);

// diagonal > 0: the mesh's bounding-box diagonal. Skeletons without bones give zero distances.
SkeletonComparison compareSkeletons(const Skeleton& truth, const Skeleton& ours, double diagonal);

}  // namespace odeskin
