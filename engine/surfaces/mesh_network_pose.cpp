// SPDX-License-Identifier: MIT
#include "mesh_network_pose.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/SparseCholesky>

#include "../core/position_box.hpp"

namespace odeskin {
namespace {

Status checkFaces(const FaceList& faces, std::size_t vertex_count) {
  for (std::uint32_t index : faces.indices) {
    if (index >= vertex_count) {
      return invalidArgument("a face uses vertex " + std::to_string(index + 1) + " of " + std::to_string(vertex_count));
    }
  }
  return okStatus();
}

// Each edge of the faces once, as (smaller, larger) index.
std::vector<std::pair<std::uint32_t, std::uint32_t>> meshEdges(const FaceList& faces) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
  for (std::size_t f = 0; f < faces.faceCount(); ++f) {
    const std::uint32_t begin = faces.face_offsets[f], end = faces.face_offsets[f + 1];
    for (std::uint32_t k = begin; k < end; ++k) {
      const std::uint32_t a = faces.indices[k], b = faces.indices[k + 1 < end ? k + 1 : begin];
      if (a != b) edges.emplace_back(std::min(a, b), std::max(a, b));
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  return edges;
}

}  // namespace

Result<PoseFlags> flagVertices(std::span<const Vec3> reference, std::span<const Vec3> pose, const FaceList& faces,
                               double ratio) {
  if (reference.size() != pose.size()) {
    return invalidArgument("the pose has " + std::to_string(pose.size()) + " vertices, the reference " +
                           std::to_string(reference.size()));
  }
  if (!(ratio > 1.0) || !std::isfinite(ratio)) return invalidArgument("the stretch ratio must be a finite number > 1");
  ODESKIN_TRY(checkFaces(faces, reference.size()));
  ODESKIN_TRY(checkedPositionBox(reference, "the reference", 1).status());
  ODESKIN_TRY(checkedPositionBox(pose, "the pose", 1).status());
  PoseFlags flags;
  flags.flagged.assign(reference.size(), 0);
  for (const auto& [a, b] : meshEdges(faces)) {
    {
      const double before = glm::distance(reference[a], reference[b]), after = glm::distance(pose[a], pose[b]);
      const double stretch = before > 0.0 ? after / before : (after > 0.0 ? INFINITY : 1.0);
      flags.max_stretch = std::max(flags.max_stretch, stretch);
      if (stretch > ratio) {
        ++flags.stretched_edges;
        flags.flagged[a] = flags.flagged[b] = 1;
      }
    }
  }
  flags.flagged_vertices = static_cast<std::size_t>(std::count(flags.flagged.begin(), flags.flagged.end(), 1));
  return flags;
}

Result<std::vector<Vec3>> fillFlagged(std::span<const Vec3> reference, std::span<const Vec3> pose, const FaceList& faces,
                                      std::span<const std::uint8_t> flagged) {
  if (reference.size() != pose.size() || flagged.size() != pose.size()) {
    return invalidArgument("fill: reference, pose and flags differ in size");
  }
  ODESKIN_TRY(checkFaces(faces, reference.size()));
  std::vector<Vec3> out(pose.begin(), pose.end());
  std::vector<std::int64_t> unknown(pose.size(), -1);
  std::int64_t count = 0;
  for (std::size_t v = 0; v < pose.size(); ++v) {
    if (flagged[v] != 0) unknown[v] = count++;
  }
  if (count == 0) return out;
  // Uniform graph Laplacian on the flagged vertices, the unflagged ones as Dirichlet data: symmetric
  // positive definite exactly when every flagged group touches an unflagged vertex.
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(count, 3);
  for (const auto& [a, b] : meshEdges(faces)) {
    for (const auto& [v, w] : {std::pair{a, b}, std::pair{b, a}}) {
      if (unknown[v] < 0) continue;
      entries.emplace_back(unknown[v], unknown[v], 1.0);
      if (unknown[w] >= 0) {
        entries.emplace_back(unknown[v], unknown[w], -1.0);
      } else {
        const Vec3 d = pose[w] - reference[w];
        rhs(unknown[v], 0) += d.x;
        rhs(unknown[v], 1) += d.y;
        rhs(unknown[v], 2) += d.z;
      }
    }
  }
  Eigen::SparseMatrix<double> matrix(count, count);
  matrix.setFromTriplets(entries.begin(), entries.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(matrix);
  const Eigen::MatrixXd d = solver.solve(rhs);
  bool positive = solver.info() == Eigen::Success && d.allFinite();
  if (positive) {
    const Eigen::VectorXd pivots = solver.vectorD();
    positive = pivots.minCoeff() > 1e-12 * pivots.maxCoeff();
  }
  if (!positive) {
    return invalidArgument("fill: a group of flagged vertices has no unflagged neighbour to interpolate from");
  }
  for (std::size_t v = 0; v < pose.size(); ++v) {
    if (unknown[v] >= 0) out[v] = reference[v] + Vec3(d(unknown[v], 0), d(unknown[v], 1), d(unknown[v], 2));
  }
  return out;
}

}  // namespace odeskin
