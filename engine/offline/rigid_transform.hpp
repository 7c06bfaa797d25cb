// SPDX-License-Identifier: MIT
// Rigid bone transforms (bind space -> pose space) and their interpolation between key poses.
#pragma once

#include <glm/gtc/quaternion.hpp>

#include "../core/types.hpp"

namespace odeskin {

struct RigidTransform {
  glm::dquat rotation{1.0, 0.0, 0.0, 0.0};  // unit quaternion (w, x, y, z)
  Vec3 translation{0.0};

  Vec3 apply(const Vec3& x) const { return rotation * x + translation; }
  BoneTransform matrix() const;
};

// Key-to-key interpolation for a segment (PIPELINE.md 3, K = 2): the rotation by slerp along the
// shortest arc, and the translation by lerp of the bone's pivot (its joint, in bind space), so a
// bone turning about its joint keeps the joint in place. Lerping the raw matrix translation would
// swing the joint off its path (0.18 of the arm length at mid-bend for a 100 degree elbow).
RigidTransform interpolateRigid(const RigidTransform& a, const RigidTransform& b, double tau, const Vec3& pivot);

// Rotation by `angle_rad` about the axis through `pivot` with direction `axis`.
RigidTransform rotationAbout(const Vec3& pivot, const Vec3& axis, double angle_rad);

}  // namespace odeskin
