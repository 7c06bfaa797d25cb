// SPDX-License-Identifier: MIT
#include "skeleton_compare.hpp"

#include <algorithm>
#include <limits>

#include <glm/geometric.hpp>

namespace odeskin {
namespace {

// Mean and max over `from` of the distance to the nearest point of `to`.
std::pair<double, double> nearest(const std::vector<Vec3>& from, const std::vector<Vec3>& to) {
  if (from.empty() || to.empty()) return {0.0, 0.0};
  double sum = 0.0, worst = 0.0;
  for (const Vec3& p : from) {
    double best = std::numeric_limits<double>::infinity();
    for (const Vec3& q : to) best = std::min(best, glm::length(p - q));
    sum += best;
    worst = std::max(worst, best);
  }
  return {sum / static_cast<double>(from.size()), worst};
}

}  // namespace

std::vector<Vec3> skeletonJoints(const Skeleton& skeleton, double merge_distance) {
  std::vector<Vec3> joints;
  auto add = [&](const Vec3& p) {
    for (const Vec3& q : joints) {
      if (glm::length(p - q) <= merge_distance) return;
    }
    joints.push_back(p);
  };
  for (std::size_t b = 0; b < skeleton.boneCount(); ++b) {
    add(skeleton.heads[b]);
    if (b < skeleton.tails.size()) add(skeleton.tails[b]);
  }
  return joints;
}

SkeletonComparison compareSkeletons(const Skeleton& truth, const Skeleton& ours, double diagonal) {
  SkeletonComparison c;
  const std::vector<Vec3> t = skeletonJoints(truth, 1e-9 * diagonal);
  const std::vector<Vec3> o = skeletonJoints(ours, 1e-9 * diagonal);
  c.truth_bones = truth.boneCount();
  c.bones = ours.boneCount();
  c.truth_joints = t.size();
  c.joints = o.size();
  const auto [tm, tx] = nearest(t, o);
  const auto [om, ox] = nearest(o, t);
  c.truth_to_ours_mean = tm / diagonal;
  c.truth_to_ours_max = tx / diagonal;
  c.ours_to_truth_mean = om / diagonal;
  c.ours_to_truth_max = ox / diagonal;
  return c;
}

}  // namespace odeskin
