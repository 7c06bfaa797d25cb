// SPDX-License-Identifier: MIT
#include "lbs_job.hpp"

#include <string>
#include <vector>

#include "dual_quaternion.hpp"

namespace odeskin {

Status LbsJob::validate() const {
  const std::size_t vertex_count = rest_positions.size();
  if (out_positions.size() != vertex_count) {
    return invalidArgument("lbs: out_positions has " + std::to_string(out_positions.size()) + " entries for " +
                           std::to_string(vertex_count) + " vertices");
  }
  if (bones.empty() && vertex_count > 0) return invalidArgument("lbs: bones is empty");
  if (skinning != SkinningMode::kLinear && skinning != SkinningMode::kDualQuaternion) {
    return invalidArgument("lbs: unknown skinning mode " + std::to_string(static_cast<std::uint32_t>(skinning)));
  }
  ODESKIN_TRY(validateBones(bones, "lbs"));
  return validateInfluences(influences, vertex_count, static_cast<std::uint32_t>(bones.size()));
}

Status LbsJob::run() const {
  ODESKIN_TRY(validate());
  if (skinning == SkinningMode::kDualQuaternion) {
    const std::vector<DualQuaternion> dual_quaternions = toDualQuaternions(bones);
    for (std::size_t i = 0; i < rest_positions.size(); ++i) {
      out_positions[i] = skinTransform(skinning, influences, bones, dual_quaternions, i).apply(rest_positions[i]);
    }
    return okStatus();
  }
  for (std::size_t i = 0; i < rest_positions.size(); ++i) {
    out_positions[i] = skinPoint(influences, bones, i, rest_positions[i]);
  }
  return okStatus();
}

Vec3 skinPoint(const InfluencesView& influences, std::span<const BoneTransform> bones, std::size_t vertex,
               const Vec3& x) {
  const glm::dvec4 h(x, 1.0);
  Vec3 p(0.0);
  for (std::uint32_t k = influences.offsets[vertex]; k < influences.offsets[vertex + 1]; ++k) {
    p += influences.weights[k] * (bones[influences.bones[k]] * h);
  }
  return p;
}

glm::dmat3 blendedLinearPart(const InfluencesView& influences, std::span<const BoneTransform> bones,
                             std::size_t vertex) {
  glm::dmat3 a(0.0);
  for (std::uint32_t k = influences.offsets[vertex]; k < influences.offsets[vertex + 1]; ++k) {
    a += influences.weights[k] * glm::dmat3(bones[influences.bones[k]]);
  }
  return a;
}

}  // namespace odeskin
