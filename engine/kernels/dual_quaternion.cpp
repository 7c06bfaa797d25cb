// SPDX-License-Identifier: MIT
#include "dual_quaternion.hpp"

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "lbs_job.hpp"

namespace odeskin {
namespace {

// Newton's polar iteration converges quadratically once close (error e -> e^2 / 2), so 1e-15 is
// reached in about 6 steps from a 30% shear and in one from a rotation; 64 caps pathological input.
constexpr int kMaxPolarIterations = 64;
constexpr double kPolarTolerance = 1e-15;

bool finite(const glm::dmat3& m) {
  for (int c = 0; c < 3; ++c) {
    for (int r = 0; r < 3; ++r) {
      if (!std::isfinite(m[c][r])) return false;
    }
  }
  return true;
}

double frobenius(const glm::dmat3& m) {
  double sum = 0.0;
  for (int c = 0; c < 3; ++c) sum += glm::dot(m[c], m[c]);
  return std::sqrt(sum);
}

// Proper rotation from the first two columns (det <= 0 fallback).
glm::dmat3 gramSchmidt(const glm::dmat3& a) {
  const double len0 = glm::length(a[0]);
  if (!(len0 > 0.0) || !std::isfinite(len0)) return glm::dmat3(1.0);
  const Vec3 c0 = a[0] / len0;
  const Vec3 rest = a[1] - glm::dot(c0, a[1]) * c0;
  const double len1 = glm::length(rest);
  if (!(len1 > 1e-12 * glm::length(a[1])) || !std::isfinite(len1)) return glm::dmat3(1.0);
  const Vec3 c1 = rest / len1;
  return glm::dmat3(c0, c1, glm::cross(c0, c1));
}

// The blend of blendDualQuaternions with bone b's dual quaternion from dual_quaternion_of(b).
template <typename DualQuaternionOf>
std::optional<DualQuaternion> blend(const InfluencesView& influences, std::size_t vertex,
                                    const DualQuaternionOf& dual_quaternion_of) {
  const std::uint32_t begin = influences.offsets[vertex];
  const std::uint32_t end = influences.offsets[vertex + 1];
  if (begin == end) return std::nullopt;
  // q and -q are the same rotation; blending them as given can cancel. Every bone is taken on the
  // pivot's side, the pivot being the largest weight (the first one on ties) so it dominates.
  std::uint32_t pivot = begin;
  for (std::uint32_t k = begin + 1; k < end; ++k) {
    if (influences.weights[k] > influences.weights[pivot]) pivot = k;
  }
  const glm::dquat pivot_real = dual_quaternion_of(influences.bones[pivot]).real;
  glm::dquat real(0.0, 0.0, 0.0, 0.0);
  glm::dquat dual(0.0, 0.0, 0.0, 0.0);
  for (std::uint32_t k = begin; k < end; ++k) {
    const DualQuaternion q = dual_quaternion_of(influences.bones[k]);
    const double w = glm::dot(q.real, pivot_real) < 0.0 ? -influences.weights[k] : influences.weights[k];
    real += w * q.real;
    dual += w * q.dual;
  }
  const double norm = glm::length(real);
  if (!(norm > kMinDualQuaternionBlendNorm) || !std::isfinite(norm)) return std::nullopt;
  return DualQuaternion{real / norm, dual / norm};
}

SkinTransform linearTransform(const InfluencesView& influences, std::span<const BoneTransform> bones,
                              std::size_t vertex) {
  SkinTransform lbs{blendedLinearPart(influences, bones, vertex), Vec3(0.0)};
  for (std::uint32_t k = influences.offsets[vertex]; k < influences.offsets[vertex + 1]; ++k) {
    lbs.translation += influences.weights[k] * bones[influences.bones[k]][3];
  }
  return lbs;
}

}  // namespace

glm::dmat3 nearestRotation(const glm::dmat3& a) {
  const double det = glm::determinant(a);
  if (!finite(a) || !(det > 0.0)) return gramSchmidt(a);
  glm::dmat3 x = a;
  for (int k = 0; k < kMaxPolarIterations; ++k) {
    const glm::dmat3 next = 0.5 * (x + glm::transpose(glm::inverse(x)));
    const double change = frobenius(next - x);
    x = next;
    if (!(change > kPolarTolerance * frobenius(x))) break;
  }
  return finite(x) ? x : gramSchmidt(a);
}

DualQuaternion DualQuaternion::fromRigid(const BoneTransform& bone) {
  DualQuaternion q;
  q.real = glm::normalize(glm::quat_cast(nearestRotation(glm::dmat3(bone))));
  const Vec3 t = bone[3];
  q.dual = 0.5 * (glm::dquat(0.0, t.x, t.y, t.z) * q.real);
  return q;
}

glm::dmat3 DualQuaternion::rotation() const { return glm::mat3_cast(real); }

Vec3 DualQuaternion::translation() const {
  const Vec3 rv(real.x, real.y, real.z);
  const Vec3 dv(dual.x, dual.y, dual.z);
  return 2.0 * (real.w * dv - dual.w * rv + glm::cross(rv, dv));
}

BoneTransform DualQuaternion::toRigid() const {
  const glm::dmat3 r = rotation();
  return BoneTransform(r[0], r[1], r[2], translation());
}

void toDualQuaternions(std::span<const BoneTransform> bones, std::span<DualQuaternion> out) {
  for (std::size_t b = 0; b < bones.size() && b < out.size(); ++b) out[b] = DualQuaternion::fromRigid(bones[b]);
}

std::vector<DualQuaternion> toDualQuaternions(std::span<const BoneTransform> bones) {
  std::vector<DualQuaternion> out(bones.size());
  toDualQuaternions(bones, out);
  return out;
}

std::optional<DualQuaternion> blendDualQuaternions(const InfluencesView& influences,
                                                   std::span<const DualQuaternion> bone_dual_quaternions,
                                                   std::size_t vertex) {
  return blend(influences, vertex, [&](std::uint32_t b) -> const DualQuaternion& { return bone_dual_quaternions[b]; });
}

SkinTransform skinTransform(SkinningMode mode, const InfluencesView& influences, std::span<const BoneTransform> bones,
                            std::size_t vertex) {
  if (mode == SkinningMode::kDualQuaternion) {
    // The vertex's own bones only, converted as they are met (the pivot's twice).
    const auto q = blend(influences, vertex, [&](std::uint32_t b) { return DualQuaternion::fromRigid(bones[b]); });
    if (q) return SkinTransform{q->rotation(), q->translation()};
  }
  return linearTransform(influences, bones, vertex);
}

SkinTransform skinTransform(SkinningMode mode, const InfluencesView& influences, std::span<const BoneTransform> bones,
                            std::span<const DualQuaternion> bone_dual_quaternions, std::size_t vertex) {
  if (mode == SkinningMode::kDualQuaternion) {
    if (const std::optional<DualQuaternion> q = blendDualQuaternions(influences, bone_dual_quaternions, vertex)) {
      return SkinTransform{q->rotation(), q->translation()};
    }
  }
  return linearTransform(influences, bones, vertex);
}

}  // namespace odeskin
