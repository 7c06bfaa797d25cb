// SPDX-License-Identifier: MIT
#include "rig.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "../core/finite_vector.hpp"
#include "../core/parallel.hpp"
#include "../kernels/lbs_job.hpp"

namespace odeskin {

Status validateRig(const Rig& rig, std::size_t vertex_count, std::size_t pose_count) {
  const Skeleton& s = rig.skeleton;
  const std::size_t bones = s.boneCount();
  if (bones == 0) return invalidArgument("rig: the skeleton has no bones");
  if (s.parents.size() != bones || s.tails.size() != bones || (!s.names.empty() && s.names.size() != bones)) {
    return invalidArgument("rig: skeleton arrays differ in size (heads " + std::to_string(bones) + ", tails " +
                           std::to_string(s.tails.size()) + ", parents " + std::to_string(s.parents.size()) +
                           ", names " + std::to_string(s.names.size()) + ")");
  }
  for (std::size_t b = 0; b < bones; ++b) {
    const std::string bone = "rig: bone " + std::to_string(b) + (s.names.empty() ? "" : " (" + s.names[b] + ")");
    if (!isFinite(s.heads[b]) || !isFinite(s.tails[b])) return invalidArgument(bone + " has a non-finite joint");
    if (s.parents[b] < -1 || s.parents[b] >= static_cast<std::int32_t>(bones)) {
      return invalidArgument(bone + " has parent " + std::to_string(s.parents[b]) + " outside -1.." +
                             std::to_string(bones - 1));
    }
    // Walking up more than B parents means a cycle.
    std::int32_t p = s.parents[b];
    for (std::size_t steps = 0; p >= 0; ++steps, p = s.parents[static_cast<std::size_t>(p)]) {
      if (steps > bones) return invalidArgument(bone + " is on a cycle of parents");
    }
  }
  if (vertex_count > 0 && rig.influences.vertexCount() > 0) {
    ODESKIN_TRY(validateInfluences(rig.influences, vertex_count, static_cast<std::uint32_t>(bones)));
  }
  if (pose_count > 0 && !rig.key_poses.empty()) {
    if (rig.key_poses.size() != pose_count) {
      return invalidArgument("rig: " + std::to_string(rig.key_poses.size()) + " sets of bone transforms for " +
                             std::to_string(pose_count) + " example poses");
    }
    for (std::size_t k = 0; k < pose_count; ++k) {
      if (rig.key_poses[k].size() != bones) {
        return invalidArgument("rig: pose " + std::to_string(k) + " has " + std::to_string(rig.key_poses[k].size()) +
                               " bone transforms for " + std::to_string(bones) + " bones");
      }
      for (std::size_t b = 0; b < bones; ++b) {
        if (!isUnitRigid(rig.key_poses[k][b])) {
          return invalidArgument("rig: pose " + std::to_string(k) + " bone " + std::to_string(b) +
                                 " has a non-finite transform or a rotation that is not unit");
        }
      }
    }
  }
  return okStatus();
}

SkinningError skinningError(std::span<const Vec3> rest, std::span<const std::vector<Vec3>> poses, const Rig& rig) {
  const std::size_t k_count = poses.size();
  std::vector<double> worst(k_count, 0.0), error_sum(k_count, 0.0), motion_sum(k_count, 0.0);
  parallelFor(std::size_t{0}, k_count, [&](std::size_t k) {
    std::vector<BoneTransform> bones;
    for (const RigidTransform& t : rig.key_poses[k]) bones.push_back(t.matrix());
    for (std::size_t i = 0; i < rest.size(); ++i) {
      const Vec3& target = poses[k][i];
      const double e = glm::length(skinPoint(rig.influences, bones, i, rest[i]) - target);
      worst[k] = std::max(worst[k], e);
      error_sum[k] += e;
      motion_sum[k] += glm::length(target - rest[i]);
    }
  });
  SkinningError out;
  out.samples = k_count * rest.size();
  for (std::size_t k = 0; k < k_count; ++k) {  // in pose order, so the sums are the same numbers every run
    out.max = std::max(out.max, worst[k]);
    out.sum += error_sum[k];
    out.motion_sum += motion_sum[k];
  }
  return out;
}

}  // namespace odeskin
