// SPDX-License-Identifier: MIT
#include "body_section.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

#include <Eigen/Eigenvalues>
#include <glm/geometric.hpp>

#include "triangle_cull.hpp"

namespace odeskin {
namespace {

// The principal axes, longest first, of the component's vertices within `reach` of `centre`
// (about `centre`); empty with fewer than 4 of them.
std::optional<std::array<Vec3, 3>> principalAxes(std::span<const Vec3> rest, std::span<const std::uint32_t> component,
                                                 const Vec3& centre, double reach) {
  Eigen::Matrix3d spread = Eigen::Matrix3d::Zero();
  std::size_t near_count = 0;
  for (const std::uint32_t v : component) {
    const Vec3 d = rest[v] - centre;
    if (glm::dot(d, d) > reach * reach) continue;
    const Eigen::Vector3d e(d.x, d.y, d.z);
    spread += e * e.transpose();
    ++near_count;
  }
  if (near_count < 4) return std::nullopt;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(spread);
  std::array<Vec3, 3> axes;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d a = solver.eigenvectors().col(2 - k);
    axes[static_cast<std::size_t>(k)] = Vec3(a.x(), a.y(), a.z());
  }
  return axes;
}

// The shortest section through `centre` (bodySection). A torso's longest principal axis is the
// one to cut across, so it is the first start.
std::optional<GirthPlane> sectionAround(std::span<const Vec3> rest, const MeshTopology& mesh,
                                        std::span<const std::uint32_t> component, std::span<const char> in_component,
                                        const Vec3& centre) {
  // Squares compared, one root taken each: the same numbers as the roots compared.
  double nearest = std::numeric_limits<double>::infinity();
  double farthest = 0.0;
  for (const std::uint32_t v : component) {
    const Vec3 d = rest[v] - centre;
    nearest = std::min(nearest, glm::dot(d, d));
    farthest = std::max(farthest, glm::dot(d, d));
  }
  nearest = std::sqrt(nearest);
  farthest = std::sqrt(farthest);
  if (!(nearest > 0.0)) return std::nullopt;
  for (double reach = 3.0 * nearest;; reach *= 2.0) {
    if (const std::optional<std::array<Vec3, 3>> starts = principalAxes(rest, component, centre, reach)) {
      if (std::optional<GirthPlane> plane = leastGirthPlane(rest, mesh, centre, reach, *starts, in_component)) return plane;
    }
    if (reach >= farthest) return std::nullopt;
  }
}

// Whether a triangle whose projection has the line's point on an edge (a weight exactly 0) holds
// it: of two triangles sharing that edge, exactly one does when they lie on either side of it, so
// that a line through an edge or a vertex crosses the surface once (the rasteriser's top-left
// rule). An edge owns the point when it runs up, or level and to the left, in the triangle's
// counter-clockwise order.
bool coversOnEdge(const std::array<double, 3>& weights, const std::array<Vec3, 3>& corners, double sum) {
  for (int i = 0; i < 3; ++i) {
    if (weights[static_cast<std::size_t>(i)] != 0.0) continue;
    Vec3 a = corners[static_cast<std::size_t>((i + 1) % 3)];
    Vec3 b = corners[static_cast<std::size_t>((i + 2) % 3)];
    if (sum < 0.0) std::swap(a, b);
    if (!(b.y > a.y || (b.y == a.y && b.x < a.x))) return false;
  }
  return true;
}

}  // namespace

Vec3 bodyCentroid(std::span<const Vec3> rest, const MeshTopology& mesh, std::span<const std::uint32_t> component,
                  std::span<const char> in_component) {
  Vec3 low = rest[component.front()];
  Vec3 high = low;
  std::size_t rim_vertices = 0;
  for (const std::uint32_t v : component) {
    low = glm::min(low, rest[v]);
    high = glm::max(high, rest[v]);
    rim_vertices += mesh.boundary_vertex[v] ? 1 : 0;
  }
  // Closed but for small holes (the horse's 19 rim edges), whose missing caps barely move the
  // volume's centroid. A mask or an open tube has no volume to speak of.
  const bool closed = rim_vertices <= component.size() / 100;
  const Vec3 origin = 0.5 * (low + high);
  // In units of the box's diagonal: volumes are cubes of lengths, which overflow for meshes the
  // rest of the rig still takes (1e150 across).
  const double unit = glm::length(high - low);
  if (!(unit > 0.0)) return origin;
  Vec3 volume_moment{0.0};
  Vec3 area_moment{0.0};
  double volume = 0.0;  // six times
  double area = 0.0;    // twice
  // Each vertex scaled once, not once for each of its (about six) triangles: a sixth of the divisions.
  std::vector<Vec3> scaled(rest.size());
  for (const std::uint32_t v : component) scaled[v] = (rest[v] - origin) / unit;
  for (const auto& corners : mesh.triangles) {
    if (!in_component[corners[0]]) continue;
    const Vec3& a = scaled[corners[0]];
    const Vec3& b = scaled[corners[1]];
    const Vec3& c = scaled[corners[2]];
    const double six_volume = glm::dot(a, glm::cross(b, c));
    volume += six_volume;
    volume_moment += (six_volume / 4.0) * (a + b + c);
    const double twice_area = glm::length(glm::cross(b - a, c - a));
    area += twice_area;
    area_moment += (twice_area / 3.0) * (a + b + c);
  }
  // A closed surface that encloses next to nothing (a flat or inside-out mesh) has no useful volume.
  if (closed && std::abs(volume) > 1e-6 * std::pow(0.5 * area, 1.5)) return origin + (unit / volume) * volume_moment;
  return area > 0.0 ? origin + (unit / area) * area_moment : origin;
}

std::optional<Vec3> longestChordMiddle(std::span<const Vec3> rest, const MeshTopology& mesh,
                                       std::span<const std::uint32_t> component, std::span<const char> in_component,
                                       const Vec3& centroid) {
  const std::optional<std::array<Vec3, 3>> axes =
      principalAxes(rest, component, centroid, std::numeric_limits<double>::infinity());
  if (!axes) return std::nullopt;
  const std::array<Vec3, 3> frame{(*axes)[2], (*axes)[1], (*axes)[0]};  // shortest first
  std::vector<Vec3> lines;
  for (int i = -1; i <= 1; ++i) {
    for (int j = -1; j <= 1; ++j) {
      for (int k = 0; k <= 1; ++k) {
        // One of each opposite pair: the first non-zero coefficient positive.
        if ((k == 0 && j < 0) || (k == 0 && j == 0 && i <= 0)) continue;
        lines.push_back(glm::normalize(double(i) * frame[0] + double(j) * frame[1] + double(k) * frame[2]));
      }
    }
  }
  std::vector<std::uint32_t> triangles;
  std::vector<Vec3> middles;
  std::vector<double> radii;
  for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& c = mesh.triangles[t];
    if (!in_component[c[0]]) continue;
    const Vec3 middle = (rest[c[0]] + rest[c[1]] + rest[c[2]]) / 3.0 - centroid;
    double squared_radius = 0.0;
    for (const std::uint32_t v : c) {
      const Vec3 d = rest[v] - centroid - middle;
      squared_radius = std::max(squared_radius, glm::dot(d, d));
    }
    triangles.push_back(t);
    middles.push_back(middle);
    radii.push_back(std::sqrt(squared_radius));
  }
  const TriangleCull cull(middles, radii);
  double longest = 0.0;
  Vec3 best{0.0};
  std::vector<double> hits;
  std::vector<std::uint32_t> near;
  for (const Vec3& direction : lines) {
    // A triangle meets the line where its projection on the plane square to the line holds the
    // line's point: in a frame (across, up, along), the origin of (across, up).
    const std::array<Vec3, 2> across = squareTo(direction);
    const Vec3 u = across[0];
    const Vec3 w = across[1];
    auto framed = [&](std::uint32_t v) {
      const Vec3 d = rest[v] - centroid;
      return Vec3(glm::dot(u, d), glm::dot(w, d), glm::dot(direction, d));
    };
    cull.nearLine(direction, near);
    hits.clear();
    for (const std::uint32_t k : near) {
      const auto& t = mesh.triangles[triangles[k]];
      const Vec3 p0 = framed(t[0]);
      const Vec3 p1 = framed(t[1]);
      const Vec3 p2 = framed(t[2]);
      // The origin's barycentric weights, unnormalised: the signed areas it spans with each edge.
      const double w0 = p1.x * p2.y - p1.y * p2.x;
      const double w1 = p2.x * p0.y - p2.y * p0.x;
      const double w2 = p0.x * p1.y - p0.y * p1.x;
      const double low = std::min(w0, std::min(w1, w2));
      const double high = std::max(w0, std::max(w1, w2));
      const double sum = w0 + w1 + w2;
      if ((low < 0.0 && high > 0.0) || sum == 0.0) continue;
      if ((low == 0.0 || high == 0.0) && !coversOnEdge({w0, w1, w2}, {p0, p1, p2}, sum)) continue;
      hits.push_back((w0 / sum) * p0.z + (w1 / sum) * p1.z + (w2 / sum) * p2.z);  // weights first: no overflow
    }
    std::sort(hits.begin(), hits.end());
    if (hits.size() % 2 != 0) continue;
    for (std::size_t h = 0; h + 1 < hits.size(); h += 2) {
      if (hits[h + 1] - hits[h] > longest) {
        longest = hits[h + 1] - hits[h];
        best = centroid + (0.5 * (hits[h] + hits[h + 1])) * direction;
      }
    }
  }
  if (!(longest > 0.0)) return std::nullopt;
  return best;
}

std::optional<GirthPlane> bodySection(std::span<const Vec3> rest, const MeshTopology& mesh,
                                      std::span<const std::uint32_t> component, std::span<const char> in_component) {
  const Vec3 centroid = bodyCentroid(rest, mesh, component, in_component);
  const Vec3 centre = longestChordMiddle(rest, mesh, component, in_component, centroid).value_or(centroid);
  return sectionAround(rest, mesh, component, in_component, centre);
}

}  // namespace odeskin
