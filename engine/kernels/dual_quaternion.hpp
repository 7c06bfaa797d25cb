// SPDX-License-Identifier: MIT
// Dual-quaternion skinning (Kavan, Collins, Zara, O'Sullivan 2008, "Geometric skinning with
// approximate dual quaternion blending", Algorithm 1): each bone's rigid transform becomes a unit
// dual quaternion q_b = r_b + eps (1/2) (0, t_b) r_b; a vertex blends them linearly,
//   b = sum_b w_ib s_b q_b   (s_b = -1 where dot(r_b, r_pivot) < 0, pivot = the highest weight),
// divides by |real(b)| and applies the resulting rigid transform. Unlike linear blend skinning
// (thesis Eq 6.1) the blend is always a rotation, so a twisted or bent joint keeps its volume
// (no candy wrapper). Mirrored in float by fourier_deform_fast_job.cpp and shaders/skinning.glsl.
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include "../core/gpu_layout.h"
#include "../core/types.hpp"
#include "influences.hpp"

namespace odeskin {

// Below this norm of the blended real part a vertex's blend has no defined rotation and the vertex
// is skinned by LBS instead. With non-negative weights summing to 1 and the antipodality fix
// against the highest-weight bone, |real(b)| >= dot(real(b), r_pivot) >= max_b w_ib >= 1/influences,
// so valid influences never reach it; it guards zero or non-finite data. The fast path and the
// shader use the same value in float.
inline constexpr double kMinDualQuaternionBlendNorm = ODESKIN_DQS_MIN_BLEND_NORM;

// q = real + eps dual. For a rigid transform x -> R x + t: real is R's unit quaternion and
// dual = 1/2 (0, t) real. glm::dquat is (w, x, y, z) in its constructor.
struct DualQuaternion {
  glm::dquat real{1.0, 0.0, 0.0, 0.0};
  glm::dquat dual{0.0, 0.0, 0.0, 0.0};

  // The rigid part of `bone`, which is assumed rigid: its 3x3 is first replaced by the nearest
  // rotation (nearestRotation), so rounding drift, scale and shear are dropped, never amplified.
  static DualQuaternion fromRigid(const BoneTransform& bone);

  // Rotation and translation of a unit dual quaternion (a blend normalised by |real|: the part of
  // `dual` along `real` is ignored, as Kavan's Algorithm 1 does).
  glm::dmat3 rotation() const;
  Vec3 translation() const;  // 2 vec(dual conj(real))
  BoneTransform toRigid() const;
};

// The rotation closest to `a` in the Frobenius norm (the orthogonal polar factor, by Higham's
// Newton iteration X <- (X + X^-T) / 2, quadratic and exact on rotations). A 3x3 with det <= 0 has
// no nearest rotation: its first two columns are Gram-Schmidt orthonormalised and the third is
// their cross product; a 3x3 without two independent finite columns gives the identity.
glm::dmat3 nearestRotation(const glm::dmat3& a);

// fromRigid of every bone (`out` at least bones.size() long).
void toDualQuaternions(std::span<const BoneTransform> bones, std::span<DualQuaternion> out);
std::vector<DualQuaternion> toDualQuaternions(std::span<const BoneTransform> bones);

// Vertex `vertex`'s blend of `bone_dual_quaternions` (one per bone, indexed by influences.bones)
// with the antipodality fix, normalised by |real|. nullopt when the row is empty or |real| <=
// kMinDualQuaternionBlendNorm (the caller falls back to LBS). Influences must be valid
// (validateInfluences); not checked here.
std::optional<DualQuaternion> blendDualQuaternions(const InfluencesView& influences,
                                                   std::span<const DualQuaternion> bone_dual_quaternions,
                                                   std::size_t vertex);

// What skinning does to one vertex, an affine map x -> linear x + translation:
//   kLinear:          (sum_b w_ib R_b, sum_b w_ib t_b)   (= blendedLinearPart, PIPELINE.md 2)
//   kDualQuaternion:  rotation and translation of the vertex's blended unit dual quaternion, or the
//                     kLinear transform where the blend is degenerate (see above).
// Either way the skinned point is linear * x + translation, and PIPELINE.md 2's bind-space residual
// is r = linear^-1 (P - skinned(X)).
struct SkinTransform {
  glm::dmat3 linear{1.0};
  Vec3 translation{0.0};

  Vec3 apply(const Vec3& x) const { return linear * x + translation; }
};

// Per vertex; in kDualQuaternion mode this converts the vertex's bones every call. Loops over many
// vertices should convert once (toDualQuaternions) and use the overload below.
SkinTransform skinTransform(SkinningMode mode, const InfluencesView& influences, std::span<const BoneTransform> bones,
                            std::size_t vertex);
// `bone_dual_quaternions`: toDualQuaternions(bones) (read in kDualQuaternion mode only).
SkinTransform skinTransform(SkinningMode mode, const InfluencesView& influences, std::span<const BoneTransform> bones,
                            std::span<const DualQuaternion> bone_dual_quaternions, std::size_t vertex);

}  // namespace odeskin
