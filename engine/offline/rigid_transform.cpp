// SPDX-License-Identifier: MIT
#include "rigid_transform.hpp"

#include <algorithm>
#include <cmath>

#include "../core/finite_vector.hpp"

namespace odeskin {

bool isUnitRigid(const RigidTransform& m) {
  const double norm = glm::length(m.rotation);
  return isFinite(m.translation) && std::isfinite(norm) && std::abs(norm - 1.0) <= 1e-6;
}

namespace {

// log and exp of unit quaternions as 3-vectors (half the rotation vector).
Vec3 quatLog(const glm::dquat& q) {
  const Vec3 v(q.x, q.y, q.z);
  const double s = glm::length(v);
  if (s < 1e-12) return v;
  return v * (std::atan2(s, q.w) / s);
}

glm::dquat quatExp(const Vec3& v) {
  const double angle = glm::length(v);
  if (angle < 1e-12) return glm::normalize(glm::dquat(1.0, v.x, v.y, v.z));
  const Vec3 axis = v * (std::sin(angle) / angle);
  return glm::dquat(std::cos(angle), axis.x, axis.y, axis.z);
}

// Slerp along the arc from a to b as given (no sign flip: squad's inner slerps need exactly that).
glm::dquat arcSlerp(const glm::dquat& a, const glm::dquat& b, double h) {
  const double cos_angle = std::clamp(glm::dot(a, b), -1.0, 1.0);
  const double angle = std::acos(cos_angle);
  if (angle < 1e-9) return glm::normalize(a + h * (b - a));
  const double sin_angle = std::sin(angle);
  return (std::sin((1.0 - h) * angle) / sin_angle) * a + (std::sin(h * angle) / sin_angle) * b;
}

}  // namespace

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

RigidKeyPath::RigidKeyPath(std::span<const RigidTransform> keys, const Vec3& pivot) : pivot_(pivot) {
  const std::size_t k_count = keys.size();
  for (std::size_t k = 0; k < k_count; ++k) {
    glm::dquat q = glm::normalize(keys[k].rotation);
    if (k > 0 && glm::dot(rotations_.back(), q) < 0.0) q = -q;
    rotations_.push_back(q);
    positions_.push_back(keys[k].apply(pivot));
  }
  for (std::size_t k = 0; k < k_count; ++k) {
    if (k == 0 || k + 1 == k_count) {
      controls_.push_back(rotations_[k]);
      const std::size_t lo = k == 0 ? 0 : k - 1;
      tangents_.push_back(k_count < 2 ? Vec3(0.0) : positions_[lo + 1] - positions_[lo]);
      continue;
    }
    const glm::dquat inv = glm::inverse(rotations_[k]);
    const Vec3 sum = quatLog(inv * rotations_[k + 1]) + quatLog(inv * rotations_[k - 1]);
    controls_.push_back(rotations_[k] * quatExp(-0.25 * sum));
    tangents_.push_back(0.5 * (positions_[k + 1] - positions_[k - 1]));
  }
}

RigidTransform RigidKeyPath::at(std::uint32_t segment, double tau) const {
  const std::size_t s = std::min<std::size_t>(segment, rotations_.size() - 2);
  const double h = std::clamp(tau, 0.0, 1.0);
  const glm::dquat outer = arcSlerp(rotations_[s], rotations_[s + 1], h);
  const glm::dquat inner = arcSlerp(controls_[s], controls_[s + 1], h);
  RigidTransform out;
  out.rotation = glm::normalize(arcSlerp(outer, inner, 2.0 * h * (1.0 - h)));
  const double h2 = h * h;
  const double h3 = h2 * h;
  const Vec3 position = (2.0 * h3 - 3.0 * h2 + 1.0) * positions_[s] + (h3 - 2.0 * h2 + h) * tangents_[s] +
                        (-2.0 * h3 + 3.0 * h2) * positions_[s + 1] + (h3 - h2) * tangents_[s + 1];
  out.translation = position - out.rotation * pivot_;
  return out;
}

RigidTransform rotationAbout(const Vec3& pivot, const Vec3& axis, double angle_rad) {
  RigidTransform out;
  out.rotation = glm::angleAxis(angle_rad, glm::normalize(axis));
  out.translation = pivot - out.rotation * pivot;
  return out;
}

}  // namespace odeskin
