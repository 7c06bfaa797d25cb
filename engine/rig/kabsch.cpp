// SPDX-License-Identifier: MIT
// Weighted Kabsch (Kabsch 1976; Umeyama 1991 without scale):
//   c_x = sum w x / sum w,  c_y = sum w y / sum w,  H = sum w (x - c_x)(y - c_y)^T = U S V^T,
//   R = V diag(1, 1, det(V U^T)) U^T,  t = c_y - R c_x.
// Bone transforms from weights are refined as in SSDR's bone step (Le & Deng 2012, section 3.2):
// with the other bones fixed, bone j minimises sum_i |p_i - sum_b w_ib T_b x_i|^2, which is a
// weighted Kabsch of x_i onto (p_i - sum_{b != j} w_ib T_b x_i) / w_ij with weights w_ij^2.
#include "kabsch.hpp"

#include <cmath>
#include <string>

#include <Eigen/Dense>

#include "../core/finite_vector.hpp"
#include "../core/number_text.hpp"
#include "../core/parallel.hpp"
#include "../core/position_box.hpp"
#include "bone_fit.hpp"

namespace odeskin {
namespace {

Eigen::Vector3d toEigen(const Vec3& p) { return {p.x, p.y, p.z}; }

}  // namespace

Result<RigidTransform> weightedKabsch(std::span<const Vec3> from, std::span<const Vec3> to,
                                      std::span<const double> weights) {
  if (from.size() != to.size() || weights.size() != from.size()) {
    return invalidArgument("kabsch: " + std::to_string(from.size()) + " source points, " + std::to_string(to.size()) +
                           " target points and " + std::to_string(weights.size()) + " weights");
  }
  double weight_sum = 0.0;
  Vec3 from_sum(0.0);
  Vec3 to_sum(0.0);
  for (std::size_t i = 0; i < from.size(); ++i) {
    const double w = weights[i];
    if (!std::isfinite(w) || w < 0.0) {
      return invalidArgument("kabsch: weight " + std::to_string(i) + " is " + messageNumber(w));
    }
    if (w == 0.0) continue;
    if (!isFinite(from[i]) || !isFinite(to[i])) {
      return invalidArgument("kabsch: point pair " + std::to_string(i) + " is not finite");
    }
    weight_sum += w;
    from_sum += w * from[i];
    to_sum += w * to[i];
  }
  if (!(weight_sum > 0.0)) return degenerate("kabsch: no point has a positive weight");
  // Second pass about the centroids: raw moments would cancel catastrophically far from the origin.
  const Vec3 from_centroid = from_sum / weight_sum;
  const Vec3 to_centroid = to_sum / weight_sum;
  Eigen::Matrix3d h = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < from.size(); ++i) {
    if (weights[i] == 0.0) continue;
    h.noalias() += weights[i] * toEigen(from[i] - from_centroid) * toEigen(to[i] - to_centroid).transpose();
  }
  // Points 1e200 apart are finite, but their products are not; the SVD would call them collinear.
  if (!h.allFinite()) {
    return invalidArgument("kabsch: the points are too far apart for double precision (their products overflow); "
                           "scale them down");
  }
  return kabschFromCovariance(h, from_centroid, to_centroid);
}

Result<RigidTransform> kabschFromCovariance(const Eigen::Matrix3d& h, const Vec3& from_centroid,
                                            const Vec3& to_centroid) {
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(h, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Vector3d& s = svd.singularValues();
  // Rank < 2: the points (or their images) lie on a line, and any turn about it fits as well.
  if (!std::isfinite(s(0)) || !(s(0) > 0.0) || s(1) <= kCollinearRatio * s(0)) {
    return degenerate("kabsch: the weighted points are collinear or coincide (singular values " +
                      messageNumber(s(0)) + ", " + messageNumber(s(1)) + ", " + messageNumber(s(2)) + ")");
  }
  const Eigen::Matrix3d& u = svd.matrixU();
  const Eigen::Matrix3d& v = svd.matrixV();
  // A reflection fits better when the best orthogonal map has det -1; flipping the axis of the
  // smallest singular value gives the best proper rotation instead.
  Eigen::Vector3d d(1.0, 1.0, (v * u.transpose()).determinant() < 0.0 ? -1.0 : 1.0);
  const Eigen::Matrix3d r = v * d.asDiagonal() * u.transpose();
  glm::dmat3 m;
  for (int col = 0; col < 3; ++col) {
    for (int row = 0; row < 3; ++row) m[col][row] = r(row, col);
  }
  RigidTransform out;
  out.rotation = glm::normalize(glm::quat_cast(m));
  out.translation = to_centroid - out.rotation * from_centroid;
  return out;
}

namespace {

// The inputs fitBoneTransforms and fitRigidBoneTransforms share, checked alike.
Status checkBoneFitInputs(std::span<const Vec3> rest, const std::vector<std::vector<Vec3>>& poses,
                          const Influences& influences, const Skeleton& skeleton) {
  ODESKIN_TRY(validateRig(Rig{skeleton, {}, {}}, 0, 0));
  const std::size_t vertex_count = rest.size();
  const std::size_t bone_count = skeleton.boneCount();
  if (vertex_count == 0) return invalidArgument("fit bone transforms: the bind mesh has no vertices");
  if (poses.empty()) return invalidArgument("fit bone transforms: no poses");
  ODESKIN_TRY(validateInfluences(influences, vertex_count, static_cast<std::uint32_t>(bone_count)));
  ODESKIN_TRY(checkedPositionBox(rest, "fit bone transforms: the bind mesh").status());
  for (std::size_t k = 0; k < poses.size(); ++k) {
    if (poses[k].size() != vertex_count) {
      return invalidArgument("fit bone transforms: pose " + std::to_string(k) + " has " +
                             std::to_string(poses[k].size()) + " vertices, the bind mesh " +
                             std::to_string(vertex_count));
    }
    ODESKIN_TRY(checkedPositionBox(poses[k], "fit bone transforms: pose " + std::to_string(k)).status());
  }
  return okStatus();
}

Result<std::vector<std::vector<RigidTransform>>> fitTransforms(std::span<const Vec3> rest,
                                                               const std::vector<std::vector<Vec3>>& poses,
                                                               const Influences& influences, const Skeleton& skeleton,
                                                               int sweeps) {
  ODESKIN_TRY(checkBoneFitInputs(rest, poses, influences, skeleton));
  const BoneFitProblem problem = makeBoneFitProblem(rest, influences, skeleton.parents);
  std::vector<std::vector<RigidTransform>> out(poses.size());
  parallelFor(std::size_t{0}, poses.size(), [&](std::size_t k) {
    out[k] = initialBoneTransforms(problem, poses[k]);
    if (sweeps > 0) refineBoneTransforms(problem, poses[k], out[k], sweeps);
  });
  return out;
}

}  // namespace

Result<std::vector<std::vector<RigidTransform>>> fitBoneTransforms(std::span<const Vec3> rest,
                                                                   const std::vector<std::vector<Vec3>>& poses,
                                                                   const Influences& influences,
                                                                   const Skeleton& skeleton) {
  return fitTransforms(rest, poses, influences, skeleton, kDefaultRefineSweeps);
}

Result<std::vector<std::vector<RigidTransform>>> fitRigidBoneTransforms(std::span<const Vec3> rest,
                                                                        const std::vector<std::vector<Vec3>>& poses,
                                                                        const Influences& influences,
                                                                        const Skeleton& skeleton) {
  return fitTransforms(rest, poses, influences, skeleton, 0);
}

}  // namespace odeskin
