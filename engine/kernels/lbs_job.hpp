// SPDX-License-Identifier: MIT
// CPU reference kernel (double): linear blend skinning, out_i = sum_b w_ib M_b X_i
// (Magnenat-Thalmann et al. 1988; thesis Eq 6.1), or dual-quaternion skinning (Kavan et al. 2008,
// dual_quaternion.hpp). Mirrored by LbsFastJob (fourier_deform_fast_job.hpp) and shaders/lbs.comp.
#pragma once

#include <span>

#include "../core/status.hpp"
#include "../core/types.hpp"
#include "influences.hpp"

namespace odeskin {

struct LbsJob {
  std::span<const Vec3> rest_positions;  // V, required
  InfluencesView influences;             // V rows, required
  std::span<const BoneTransform> bones;  // B, required
  std::span<Vec3> out_positions;         // V, required
  SkinningMode skinning = SkinningMode::kLinear;  // kDualQuaternion: bones are taken as rigid

  // kInvalidArgument naming the field: sizes, bone index out of range, a non-finite bone, unknown
  // skinning mode.
  Status validate() const;
  Status run() const;
};

// sum_b w_ib M_b x for vertex i's influences applied to an arbitrary point x (the LBS map L_i).
Vec3 skinPoint(const InfluencesView& influences, std::span<const BoneTransform> bones, std::size_t vertex,
               const Vec3& x);

// The blended linear part A_i = sum_b w_ib R_b of vertex i (PIPELINE.md 2), as a 3x3 matrix.
glm::dmat3 blendedLinearPart(const InfluencesView& influences, std::span<const BoneTransform> bones,
                             std::size_t vertex);

}  // namespace odeskin
