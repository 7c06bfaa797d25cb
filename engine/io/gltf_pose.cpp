// SPDX-License-Identifier: MIT
#include "gltf_pose.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>
#include <glm/gtc/quaternion.hpp>

namespace odeskin::gltf {

std::vector<Vec3> morph(std::span<const Vec3> base, const std::vector<std::vector<Vec3>>& deltas,
                        std::span<const double> weights) {
  std::vector<Vec3> out(base.begin(), base.end());
  for (std::size_t k = 0; k < deltas.size() && k < weights.size(); ++k) {
    if (weights[k] == 0.0) continue;
    for (std::size_t i = 0; i < out.size(); ++i) out[i] += weights[k] * deltas[k][i];
  }
  return out;
}

std::optional<RigidTransform> rigidPart(const glm::dmat4& skin, double& deviation) {
  Eigen::Matrix3d a;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) a(r, c) = skin[c][r];
  }
  deviation = 0.0;
  if (!(a.determinant() > 0.0)) return std::nullopt;
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(a, Eigen::ComputeFullU | Eigen::ComputeFullV);
  for (int i = 0; i < 3; ++i) deviation = std::max(deviation, std::abs(svd.singularValues()(i) - 1.0));
  const Eigen::Matrix3d rotation = svd.matrixU() * svd.matrixV().transpose();
  glm::dmat3 r;
  for (int row = 0; row < 3; ++row) {
    for (int c = 0; c < 3; ++c) r[c][row] = rotation(row, c);
  }
  RigidTransform out;
  out.rotation = glm::normalize(glm::quat_cast(r));
  out.translation = Vec3(skin[3]);
  return out;
}

}  // namespace odeskin::gltf
