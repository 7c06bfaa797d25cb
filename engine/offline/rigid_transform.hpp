// SPDX-License-Identifier: MIT
// Rigid bone transforms (bind space -> pose space) and their interpolation between key poses.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include "../core/types.hpp"

namespace odeskin {

struct RigidTransform {
  glm::dquat rotation{1.0, 0.0, 0.0, 0.0};  // unit quaternion (w, x, y, z)
  Vec3 translation{0.0};

  Vec3 apply(const Vec3& x) const { return rotation * x + translation; }
  BoneTransform matrix() const;
};

// A finite translation and a rotation of unit length within 1e-6: what rigs and assets require of
// every key transform (a NaN there plays as NaN positions on every backend).
bool isUnitRigid(const RigidTransform& m);

// Key-to-key interpolation for a segment (PIPELINE.md 3, K = 2): the rotation by slerp along the
// shortest arc, and the translation by lerp of the bone's pivot (its joint, in bind space), so a
// bone turning about its joint keeps the joint in place. Lerping the raw matrix translation would
// swing the joint off its path (0.18 of the arm length at mid-bend for a 100 degree elbow).
RigidTransform interpolateRigid(const RigidTransform& a, const RigidTransform& b, double tau, const Vec3& pivot);

// One bone's path through K >= 2 key transforms, C1 across keys (PIPELINE.md 3): the rotation by
// squad (Shoemake 1987; its inner control points make the angular velocity continuous at keys), the
// pivot's position by a Catmull-Rom cubic Hermite (one-sided end tangents). With K = 2 both reduce
// to interpolateRigid: the end tangents give a straight line and squad becomes slerp.
class RigidKeyPath {
 public:
  RigidKeyPath() = default;
  RigidKeyPath(std::span<const RigidTransform> keys, const Vec3& pivot);

  std::size_t keyCount() const { return rotations_.size(); }
  // Segment s in [0, K-2] (from key s to s+1), tau in [0, 1].
  RigidTransform at(std::uint32_t segment, double tau) const;

 private:
  Vec3 pivot_{0.0};
  std::vector<glm::dquat> rotations_;  // signs aligned so consecutive keys take the short arc
  std::vector<glm::dquat> controls_;   // squad's inner quadrangle points s_k
  std::vector<Vec3> positions_;        // the pivot at each key
  std::vector<Vec3> tangents_;         // d position / d key index at each key
};

// Rotation by `angle_rad` about the axis through `pivot` with direction `axis`.
RigidTransform rotationAbout(const Vec3& pivot, const Vec3& axis, double angle_rad);

}  // namespace odeskin
