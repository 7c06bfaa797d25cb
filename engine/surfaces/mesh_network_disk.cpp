// SPDX-License-Identifier: MIT
#include "mesh_network_disk.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <unordered_map>

#include <Eigen/Dense>
#include <Eigen/SparseLU>

#include "../core/position_box.hpp"

namespace odeskin {
namespace {

std::uint64_t edgeKey(std::uint32_t a, std::uint32_t b) { return (std::uint64_t{a} << 32) | b; }

std::string edgeText(std::uint32_t a, std::uint32_t b) {
  return "edge (" + std::to_string(a + 1) + ", " + std::to_string(b + 1) + ")";  // 1-based, as in OBJ files
}

// The faces as triangles (polygons as fans from their first corner).
Result<std::vector<std::array<std::uint32_t, 3>>> triangulate(const FaceList& faces, std::size_t vertex_count) {
  std::vector<std::array<std::uint32_t, 3>> triangles;
  for (std::size_t f = 0; f < faces.faceCount(); ++f) {
    const std::uint32_t begin = faces.face_offsets[f], end = faces.face_offsets[f + 1];
    if (end - begin < 3) return invalidArgument("face " + std::to_string(f + 1) + " has fewer than 3 corners");
    for (std::uint32_t k = begin; k < end; ++k) {
      if (faces.indices[k] >= vertex_count) {
        return invalidArgument("face " + std::to_string(f + 1) + " uses vertex " + std::to_string(faces.indices[k] + 1) +
                               " of " + std::to_string(vertex_count));
      }
    }
    for (std::uint32_t k = begin + 1; k + 1 < end; ++k) {
      triangles.push_back({faces.indices[begin], faces.indices[k], faces.indices[k + 1]});
    }
  }
  if (triangles.empty()) return invalidArgument("the mesh has no faces");
  return triangles;
}

// Boundary loops, each in the direction of its faces' edges. Errors for non-manifold edges and
// vertices where loops touch.
Result<std::vector<std::vector<std::uint32_t>>> boundaryLoops(const std::vector<std::array<std::uint32_t, 3>>& triangles,
                                                              std::size_t vertex_count) {
  std::unordered_map<std::uint64_t, std::uint32_t> directed;
  directed.reserve(triangles.size() * 3);
  for (const auto& t : triangles) {
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = t[k], b = t[(k + 1) % 3];
      if (a == b) return invalidArgument(edgeText(a, b) + " joins a vertex to itself");
      if (++directed[edgeKey(a, b)] > 1) {
        return invalidArgument(edgeText(a, b) +
                               " is used twice in one direction: the mesh is not manifold or its faces are not "
                               "consistently oriented");
      }
    }
  }
  std::vector<std::int64_t> next(vertex_count, -1);
  for (const auto& [key, count] : directed) {
    const auto a = static_cast<std::uint32_t>(key >> 32), b = static_cast<std::uint32_t>(key & 0xffffffffu);
    if (directed.count(edgeKey(b, a)) != 0) continue;
    if (next[a] >= 0) return invalidArgument("vertex " + std::to_string(a + 1) + " is where two boundary loops touch");
    next[a] = b;
  }
  std::vector<std::vector<std::uint32_t>> loops;
  std::vector<bool> seen(vertex_count, false);
  for (std::uint32_t start = 0; start < vertex_count; ++start) {
    if (next[start] < 0 || seen[start]) continue;
    std::vector<std::uint32_t> loop;
    for (std::uint32_t v = start; !seen[v]; v = static_cast<std::uint32_t>(next[v])) {
      seen[v] = true;
      loop.push_back(v);
      if (next[v] < 0) return internalError("boundary walk left the boundary at vertex " + std::to_string(v + 1));
    }
    loops.push_back(std::move(loop));
  }
  return loops;
}

double loopLength(const std::vector<std::uint32_t>& loop, std::span<const Vec3> x) {
  double length = 0.0;
  for (std::size_t k = 0; k < loop.size(); ++k) length += glm::distance(x[loop[k]], x[loop[(k + 1) % loop.size()]]);
  return length;
}

// One piece, and V - E + F = 1 once the holes are filled.
Status checkDisk(const std::vector<std::array<std::uint32_t, 3>>& triangles, std::size_t disk_vertices) {
  std::vector<std::uint32_t> parent(disk_vertices);
  for (std::uint32_t i = 0; i < parent.size(); ++i) parent[i] = i;
  auto root = [&](std::uint32_t v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  std::vector<bool> used(disk_vertices, false);
  std::unordered_map<std::uint64_t, bool> edges;
  for (const auto& t : triangles) {
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = t[k], b = t[(k + 1) % 3];
      used[a] = true;
      edges[edgeKey(std::min(a, b), std::max(a, b))] = true;
      parent[root(a)] = root(b);
    }
  }
  for (std::uint32_t v = 0; v < disk_vertices; ++v) {
    if (!used[v]) return invalidArgument("vertex " + std::to_string(v + 1) + " is in no face");
  }
  for (std::uint32_t v = 1; v < disk_vertices; ++v) {
    if (root(v) != root(0)) {
      return invalidArgument("the mesh is in several pieces (vertices 1 and " + std::to_string(v + 1) +
                             " are not connected); one piece with one rim is needed");
    }
  }
  const auto euler = static_cast<std::int64_t>(disk_vertices) - static_cast<std::int64_t>(edges.size()) +
                     static_cast<std::int64_t>(triangles.size());
  if (euler != 1) {
    return invalidArgument("the mesh is not a disk once its holes are filled (V - E + F = " + std::to_string(euler) +
                           ", a disk has 1): it has handles");
  }
  return okStatus();
}

struct PrincipalAxes {
  Vec3 width{1.0, 0.0, 0.0};   // the widest direction (v)
  Vec3 height{0.0, 1.0, 0.0};  // the second (u)
};

PrincipalAxes principalAxes(std::span<const Vec3> x, std::span<const std::array<std::uint32_t, 3>> triangles) {
  Vec3 mean(0.0);
  for (const Vec3& p : x) mean += p;
  mean /= static_cast<double>(x.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const Vec3& p : x) {
    const Eigen::Vector3d d(p.x - mean.x, p.y - mean.y, p.z - mean.z);
    covariance += d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(covariance);  // ascending eigenvalues
  const Eigen::Vector3d e1 = eigen.eigenvectors().col(2), e2 = eigen.eigenvectors().col(1);
  PrincipalAxes axes{{e1.x(), e1.y(), e1.z()}, {e2.x(), e2.y(), e2.z()}};
  // The solver's signs are arbitrary: u increases along the height axis's largest component (up
  // for a face with y up), and v follows from the faces' orientation.
  Eigen::Index largest = 0;
  e2.cwiseAbs().maxCoeff(&largest);
  if (e2(largest) < 0.0) axes.height = -axes.height;
  Vec3 normal(0.0);
  for (const auto& t : triangles) normal += glm::cross(x[t[1]] - x[t[0]], x[t[2]] - x[t[0]]);
  if (glm::dot(normal, glm::cross(axes.height, axes.width)) < 0.0) axes.width = -axes.width;
  return axes;
}

// Rotates `rim` to start at the (0, 0) corner and orders it (0, 0) -> (0, 1) -> (1, 1) -> (1, 0).
Result<std::array<std::uint32_t, 4>> placeCorners(std::vector<std::uint32_t>& rim, std::span<const Vec3> x,
                                                  const PrincipalAxes& axes) {
  if (rim.size() < 4) return invalidArgument("the rim has " + std::to_string(rim.size()) + " vertices; 4 corners need at least 4");
  const Vec3 directions[4] = {-axes.width - axes.height, axes.width - axes.height, axes.width + axes.height,
                              -axes.width + axes.height};
  std::array<std::size_t, 4> at{};
  for (int c = 0; c < 4; ++c) {
    at[c] = static_cast<std::size_t>(std::max_element(rim.begin(), rim.end(), [&](std::uint32_t a, std::uint32_t b) {
                                       return glm::dot(x[a], directions[c]) < glm::dot(x[b], directions[c]);
                                     }) - rim.begin());
  }
  std::rotate(rim.begin(), rim.begin() + static_cast<std::ptrdiff_t>(at[0]), rim.end());
  const std::size_t n = rim.size();
  auto offsets = [&](bool reversed) {
    std::array<std::size_t, 4> q{};
    for (int c = 0; c < 4; ++c) {
      const std::size_t forward = (at[c] + n - at[0]) % n;
      q[c] = reversed ? (n - forward) % n : forward;
    }
    return q;
  };
  std::array<std::size_t, 4> q = offsets(false);
  bool ordered = q[0] < q[1] && q[1] < q[2] && q[2] < q[3];
  if (!ordered) {
    q = offsets(true);
    ordered = q[0] < q[1] && q[1] < q[2] && q[2] < q[3];
    if (ordered) std::reverse(rim.begin() + 1, rim.end());
  }
  if (!ordered) {
    return invalidArgument("the rim's four corners (its extremes along the diagonals of the principal directions) "
                           "do not follow each other around it; the outline is too far from convex");
  }
  return std::array<std::uint32_t, 4>{rim[q[0]], rim[q[1]], rim[q[2]], rim[q[3]]};
}

// Chord-length positions of the rim on the square's boundary.
void placeRim(MeshDisk& disk, std::span<const Vec3> x) {
  const Vec2 square[4] = {{0.0, 0.0}, {0.0, 1.0}, {1.0, 1.0}, {1.0, 0.0}};
  const std::size_t n = disk.rim.size();
  std::size_t k = 0;
  for (int side = 0; side < 4; ++side) {
    const std::uint32_t end_vertex = disk.corners[(side + 1) % 4];
    std::size_t end = k;
    double length = 0.0;
    std::vector<double> along{0.0};
    do {
      length += glm::distance(x[disk.rim[end % n]], x[disk.rim[(end + 1) % n]]);
      along.push_back(length);
      ++end;
    } while (disk.rim[end % n] != end_vertex);
    for (std::size_t i = 0; i + 1 < along.size(); ++i) {
      const double t = length > 0.0 ? along[i] / length : 0.0;
      disk.uv[disk.rim[(k + i) % n]] = square[side] + t * (square[(side + 1) % 4] - square[side]);
    }
    k = end;
  }
}

// Mean-value weights of the disk's triangles, solved for the interior vertices.
Status placeInterior(MeshDisk& disk, std::span<const Vec3> x) {
  const std::size_t n = disk.diskVertexCount();
  std::vector<bool> on_rim(n, false);
  for (std::uint32_t v : disk.rim) on_rim[v] = true;
  std::vector<std::int64_t> unknown(n, -1);
  std::int64_t count = 0;
  for (std::size_t v = 0; v < n; ++v) {
    if (!on_rim[v]) unknown[v] = count++;
  }
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(count, 2);
  for (std::size_t f = 0; f < disk.triangles.size(); ++f) {
    const auto& t = disk.triangles[f];
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t i = t[k], j = t[(k + 1) % 3], l = t[(k + 2) % 3];
      if (on_rim[i]) continue;
      const Vec3 a = x[j] - x[i], b = x[l] - x[i];
      const double la = glm::length(a), lb = glm::length(b);
      const std::string face = "triangle " + std::to_string(f + 1);
      if (!(la > 0.0) || !(lb > 0.0)) return invalidArgument(face + " has a zero-length edge at vertex " + std::to_string(i + 1));
      const double cosine = glm::dot(a, b) / (la * lb), sine = glm::length(glm::cross(a, b)) / (la * lb);
      if (1.0 + cosine <= 1e-12) {
        return invalidArgument(face + " has a straight angle at vertex " + std::to_string(i + 1) +
                               ": its mean-value weight is infinite");
      }
      const double half_tan = sine / (1.0 + cosine);  // tan(angle / 2)
      for (const auto& [other, length] : {std::pair{j, la}, std::pair{l, lb}}) {
        const double w = half_tan / length;
        entries.emplace_back(unknown[i], unknown[i], w);
        if (unknown[other] >= 0) {
          entries.emplace_back(unknown[i], unknown[other], -w);
        } else {
          rhs(unknown[i], 0) += w * disk.uv[other].x;
          rhs(unknown[i], 1) += w * disk.uv[other].y;
        }
      }
    }
  }
  if (count == 0) return okStatus();
  Eigen::SparseMatrix<double> matrix(count, count);
  matrix.setFromTriplets(entries.begin(), entries.end());
  Eigen::SparseLU<Eigen::SparseMatrix<double>> solver;
  solver.compute(matrix);
  if (solver.info() != Eigen::Success) return illPosed("mean-value parameterisation: the linear system is singular");
  const Eigen::MatrixXd solution = solver.solve(rhs);
  if (solver.info() != Eigen::Success || !solution.allFinite()) {
    return illPosed("mean-value parameterisation: the linear solve failed");
  }
  for (std::size_t v = 0; v < n; ++v) {
    if (unknown[v] < 0) continue;
    // Interior points lie inside the square; clamp the rounding at its edges.
    disk.uv[v] = glm::clamp(Vec2(solution(unknown[v], 0), solution(unknown[v], 1)), Vec2(0.0), Vec2(1.0));
  }
  return okStatus();
}

}  // namespace

std::vector<Vec3> diskPositions(const MeshDisk& disk, std::span<const Vec3> positions) {
  std::vector<Vec3> out(positions.begin(), positions.end());
  for (const std::vector<std::uint32_t>& hole : disk.holes) {
    Vec3 centre(0.0);
    for (std::uint32_t v : hole) centre += positions[v];
    out.push_back(centre / static_cast<double>(hole.size()));
  }
  return out;
}

Result<MeshDisk> parameteriseDisk(std::span<const Vec3> positions, const FaceList& faces) {
  if (positions.size() < 3) return invalidArgument("a mesh needs at least 3 vertices, got " + std::to_string(positions.size()));
  if (positions.size() >= (std::size_t{1} << 31)) return invalidArgument("too many vertices");
  ODESKIN_TRY(checkedPositionBox(positions, "", 1).status());
  MeshDisk disk;
  disk.vertex_count = positions.size();
  ODESKIN_ASSIGN_OR_RETURN(disk.triangles, triangulate(faces, positions.size()));
  ODESKIN_ASSIGN_OR_RETURN(std::vector<std::vector<std::uint32_t>> loops, boundaryLoops(disk.triangles, positions.size()));
  if (loops.empty()) return invalidArgument("the mesh is closed: an open surface with a rim is needed");
  const auto rim = std::max_element(loops.begin(), loops.end(), [&](const auto& a, const auto& b) {
    return loopLength(a, positions) < loopLength(b, positions);
  });
  disk.rim = *rim;
  for (auto it = loops.begin(); it != loops.end(); ++it) {
    if (it == rim) continue;
    const auto centre = static_cast<std::uint32_t>(disk.vertex_count + disk.holes.size());
    // Fan triangles run against the loop's direction, as the missing faces would.
    for (std::size_t k = 0; k < it->size(); ++k) disk.triangles.push_back({(*it)[(k + 1) % it->size()], (*it)[k], centre});
    disk.holes.push_back(*it);
  }
  ODESKIN_TRY(checkDisk(disk.triangles, disk.diskVertexCount()));
  const std::vector<Vec3> x = diskPositions(disk, positions);
  const std::size_t mesh_triangles = disk.triangles.size() - [&] {
    std::size_t fans = 0;
    for (const auto& hole : disk.holes) fans += hole.size();
    return fans;
  }();
  const PrincipalAxes axes = principalAxes(positions, std::span(disk.triangles).first(mesh_triangles));
  ODESKIN_ASSIGN_OR_RETURN(disk.corners, placeCorners(disk.rim, positions, axes));
  disk.uv.assign(disk.diskVertexCount(), Vec2(0.0));
  placeRim(disk, x);
  ODESKIN_TRY(placeInterior(disk, x));
  return disk;
}

}  // namespace odeskin
