// SPDX-License-Identifier: MIT
#include "cluster_skeleton.hpp"

#include <map>
#include <string>

#include <Eigen/Dense>

namespace odeskin {
namespace {

// Weight of the regulariser per pose: a relative turn of theta contributes about 2 (1 - cos theta)
// per pose along the directions it determines, so 0.01 lets turns above ~6 degrees place the joint
// and pins it to the shared boundary where the bones barely turn relative to each other.
constexpr double kJointPull = 0.01;

struct Boundary {
  std::size_t edges = 0;
  Vec3 midpoint_sum{0.0};
};

Eigen::Matrix3d toEigen(const glm::dmat3& m) {
  Eigen::Matrix3d out;
  for (int c = 0; c < 3; ++c) {
    for (int r = 0; r < 3; ++r) out(r, c) = m[c][r];
  }
  return out;
}

Vec3 jointBetween(const std::vector<std::vector<RigidTransform>>& t, std::size_t child, std::size_t parent,
                  const Vec3& boundary) {
  const double mu = kJointPull * static_cast<double>(t.size());
  Eigen::Matrix3d a = mu * Eigen::Matrix3d::Identity();
  Eigen::Vector3d rhs = mu * Eigen::Vector3d(boundary.x, boundary.y, boundary.z);
  for (const std::vector<RigidTransform>& pose : t) {
    const Eigen::Matrix3d dr = toEigen(glm::mat3_cast(pose[child].rotation)) - toEigen(glm::mat3_cast(pose[parent].rotation));
    const Vec3 dt = pose[child].translation - pose[parent].translation;
    a += dr.transpose() * dr;
    rhs -= dr.transpose() * Eigen::Vector3d(dt.x, dt.y, dt.z);
  }
  const Eigen::Vector3d j = a.ldlt().solve(rhs);
  return {j(0), j(1), j(2)};
}

}  // namespace

Skeleton skeletonFromClusters(const MotionData& m, std::span<const std::uint32_t> labels,
                              const std::vector<std::vector<RigidTransform>>& transforms) {
  const std::size_t clusters = transforms[0].size();
  std::vector<std::size_t> size(clusters, 0);
  std::vector<Vec3> centroid(clusters, Vec3(0.0));
  std::map<std::pair<std::uint32_t, std::uint32_t>, Boundary> boundaries;  // (low, high) cluster
  for (std::uint32_t i = 0; i < m.vertexCount(); ++i) {
    ++size[labels[i]];
    centroid[labels[i]] += m.rest[i];
    for (const std::uint32_t j : m.adjacency->of(i)) {
      if (j <= i || labels[j] == labels[i]) continue;
      Boundary& b = boundaries[{std::min(labels[i], labels[j]), std::max(labels[i], labels[j])}];
      ++b.edges;
      b.midpoint_sum += 0.5 * (m.rest[i] + m.rest[j]);
    }
  }
  for (std::size_t c = 0; c < clusters; ++c) centroid[c] /= static_cast<double>(std::max<std::size_t>(size[c], 1));

  Skeleton s;
  s.parents.assign(clusters, -1);
  s.heads = centroid;
  s.tails = centroid;
  for (std::size_t c = 0; c < clusters; ++c) s.names.push_back("auto_" + std::to_string(c));
  // Prim's algorithm, one tree per connected part, each rooted at its largest remaining cluster.
  std::vector<char> in_tree(clusters, 0);
  for (std::size_t placed = 0; placed < clusters;) {
    std::size_t root = clusters;
    for (std::size_t c = 0; c < clusters; ++c) {
      if (!in_tree[c] && (root == clusters || size[c] > size[root])) root = c;
    }
    in_tree[root] = 1;
    ++placed;
    for (;;) {
      const Boundary* best = nullptr;
      std::size_t child = 0;
      std::size_t parent = 0;
      for (const auto& [pair, b] : boundaries) {
        const bool first_in = in_tree[pair.first] != 0;
        if (first_in == (in_tree[pair.second] != 0)) continue;
        if (best == nullptr || b.edges > best->edges) {
          best = &b;
          parent = first_in ? pair.first : pair.second;
          child = first_in ? pair.second : pair.first;
        }
      }
      if (best == nullptr) break;
      in_tree[child] = 1;
      ++placed;
      s.parents[child] = static_cast<std::int32_t>(parent);
      s.heads[child] = jointBetween(transforms, child, parent, best->midpoint_sum / static_cast<double>(best->edges));
    }
  }
  return s;
}

}  // namespace odeskin
