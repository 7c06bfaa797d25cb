// SPDX-License-Identifier: MIT
#include "rigid_transform.hpp"

namespace odeskin {

BoneTransform RigidTransform::matrix() const {
  const glm::dmat3 r = glm::mat3_cast(rotation);
  return BoneTransform(r[0], r[1], r[2], translation);
}

RigidTransform interpolateRigid(const RigidTransform& a, const RigidTransform& b, double tau, const Vec3& pivot) {
  glm::dquat qb = b.rotation;
  if (glm::dot(a.rotation, qb) < 0.0) qb = -qb;  // shortest arc
  RigidTransform out;
  out.rotation = glm::normalize(glm::slerp(a.rotation, qb, tau));
  const Vec3 pivot_a = a.apply(pivot);
  const Vec3 pivot_b = b.apply(pivot);
  const Vec3 pivot_t = (1.0 - tau) * pivot_a + tau * pivot_b;
  out.translation = pivot_t - out.rotation * pivot;
  return out;
}

RigidTransform rotationAbout(const Vec3& pivot, const Vec3& axis, double angle_rad) {
  RigidTransform out;
  out.rotation = glm::angleAxis(angle_rad, glm::normalize(axis));
  out.translation = pivot - out.rotation * pivot;
  return out;
}

}  // namespace odeskin
