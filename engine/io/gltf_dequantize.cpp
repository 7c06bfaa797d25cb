// SPDX-License-Identifier: MIT
#include "gltf_dequantize.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

#include "../core/number_text.hpp"

namespace odeskin::gltf {
namespace {

struct Polar {
  Eigen::Matrix3d rotation;
  Eigen::Matrix3d scale;  // symmetric positive definite
  double deviation = 0.0;  // max |singular value - 1|
};

// A = R P from the SVD A = U S V^T: R = U V^T, P = V S V^T. Empty when A reflects or is singular.
std::optional<Polar> polar(const glm::dmat4& m) {
  Eigen::Matrix3d a;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) a(r, c) = m[c][r];
  }
  if (!(a.determinant() > 0.0)) return std::nullopt;
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(a, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Polar out;
  out.rotation = svd.matrixU() * svd.matrixV().transpose();
  out.scale = svd.matrixV() * svd.singularValues().asDiagonal() * svd.matrixV().transpose();
  for (int i = 0; i < 3; ++i) out.deviation = std::max(out.deviation, std::abs(svd.singularValues()(i) - 1.0));
  return out;
}

}  // namespace

Result<std::optional<Dequantization>> sharedSkinScale(std::span<const glm::dmat4> rest_skin,
                                                      std::span<const std::string> joint_names, double tolerance,
                                                      const std::string& what) {
  std::vector<Polar> parts;
  parts.reserve(rest_skin.size());
  bool rigid = true;
  for (std::size_t j = 0; j < rest_skin.size(); ++j) {
    const std::optional<Polar> p = polar(rest_skin[j]);
    if (!p) {
      return parseError(what + ": joint " + std::to_string(j) + " '" + joint_names[j] +
                        "' reflects or collapses the mesh in the rest pose (its skin matrix has determinant <= 0)");
    }
    rigid = rigid && p->deviation <= tolerance;
    parts.push_back(*p);
  }
  if (rigid || parts.empty()) return std::optional<Dequantization>();
  const Eigen::Matrix3d& shared = parts.front().scale;
  const double size = shared.norm();
  for (std::size_t j = 1; j < parts.size(); ++j) {
    const double difference = (parts[j].scale - shared).norm() / size;
    if (difference > tolerance) {
      return parseError(what + ": in the rest pose joint " + std::to_string(j) + " '" + joint_names[j] +
                        "' scales the mesh differently from joint 0 '" + joint_names[0] + "' (by " +
                        messageNumber(difference) +
                        " relative); odeskin reads a scale in the skin only when every joint shares it, as "
                        "KHR_mesh_quantization's dequantization does");
    }
  }
  Dequantization d;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) d.linear[c][r] = shared(r, c);
  }
  const Eigen::Vector3d t(rest_skin[0][3][0], rest_skin[0][3][1], rest_skin[0][3][2]);
  const Eigen::Vector3d offset = parts.front().rotation.transpose() * t;
  d.offset = glm::dvec3(offset.x(), offset.y(), offset.z());
  return std::optional<Dequantization>(d);
}

void dequantizeMesh(const Dequantization& d, MeshData& mesh) {
  for (Vec3& p : mesh.positions) p = d.linear * p + d.offset;
  for (std::vector<Vec3>& target : mesh.target_deltas) {
    for (Vec3& delta : target) delta = d.linear * delta;
  }
  const glm::dmat3 normal_map = glm::transpose(glm::inverse(d.linear));
  for (Vec3& n : mesh.normals) {
    const Vec3 mapped = normal_map * n;
    const double length = glm::length(mapped);
    if (std::isfinite(length) && length > 0.0) n = mapped / length;
  }
}

void dequantizeInverseBinds(const Dequantization& d, std::vector<glm::dmat4>& inverse_bind) {
  glm::dmat4 forward(d.linear);
  forward[3] = glm::dvec4(d.offset, 1.0);
  const glm::dmat4 inverse = glm::inverse(forward);
  for (glm::dmat4& m : inverse_bind) m = m * inverse;
}

}  // namespace odeskin::gltf
