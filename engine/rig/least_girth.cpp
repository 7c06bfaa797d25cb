// SPDX-License-Identifier: MIT
#include "least_girth.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include <glm/geometric.hpp>

#include "triangle_cull.hpp"

namespace odeskin {
namespace {

// The pattern search: the best of eight neighbours a step away, moved to while it is shorter (at
// most kMovesPerStep times), then the step halved, from 16 degrees down to half a degree. Four
// neighbours cost half as much and stop at the same sections on the data to 1e-5, except on the
// curled cat-07, where they stop at one 0.5% longer.
constexpr int kRefineRounds = 6;
constexpr int kRefineNeighbours = 8;
constexpr int kMovesPerStep = 8;
constexpr double kFirstStep = 0.28;

// The triangles wholly inside the ball, renumbered densely (their corners and edges in the order
// the triangles first name them): each plane tried walks them all, and the mesh's own numbering
// may scatter them over memory.
struct Ball {
  std::vector<Vec3> positions;                         // per ball vertex
  std::vector<std::array<std::uint32_t, 3>> corners;   // per ball triangle
  TriangleCull cull;                                   // the ball's triangles about its centre
  std::vector<std::array<std::uint32_t, 3>> edges;     // per ball triangle: edge k runs from corner k to k + 1
  std::vector<std::uint32_t> mesh_edge;                // per ball edge
  std::vector<std::array<std::uint32_t, 2>> ends;      // per ball edge: its ball vertices, the mesh's order
  std::vector<char> rim;                               // per ball edge: on a hole's rim (one triangle)
};

Ball ballAround(std::span<const Vec3> positions, const MeshTopology& mesh, const Vec3& centre, double reach,
                std::span<const char> include) {
  constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
  Ball ball;
  std::vector<char> inside(positions.size(), 0);
  for (std::uint32_t v = 0; v < positions.size(); ++v) {
    const Vec3 d = positions[v] - centre;
    inside[v] = (include.empty() || include[v]) && glm::dot(d, d) <= reach * reach ? 1 : 0;
  }
  std::vector<std::uint32_t> local_vertex(positions.size(), kNone);
  std::vector<std::uint32_t> local_edge(mesh.edges.size(), kNone);
  std::vector<Vec3> middles;
  std::vector<double> radii;
  for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& corners = mesh.triangles[t];
    if (!inside[corners[0]] || !inside[corners[1]] || !inside[corners[2]]) continue;
    std::array<std::uint32_t, 3> local_corners{};
    std::array<std::uint32_t, 3> local_edges{};
    for (int k = 0; k < 3; ++k) {
      std::uint32_t& v = local_vertex[corners[k]];
      if (v == kNone) {
        v = static_cast<std::uint32_t>(ball.positions.size());
        ball.positions.push_back(positions[corners[k]]);
      }
      local_corners[k] = v;
      const std::uint32_t mesh_e = mesh.triangle_edges[t][k];
      std::uint32_t& e = local_edge[mesh_e];
      if (e == kNone) {
        e = static_cast<std::uint32_t>(ball.mesh_edge.size());
        ball.mesh_edge.push_back(mesh_e);
        ball.ends.push_back({kNone, kNone});
      }
      local_edges[k] = e;
    }
    ball.corners.push_back(local_corners);
    ball.edges.push_back(local_edges);
    const Vec3 middle = (positions[corners[0]] + positions[corners[1]] + positions[corners[2]]) / 3.0;
    double squared_radius = 0.0;
    for (const std::uint32_t c : corners) {
      const Vec3 d = positions[c] - middle;
      squared_radius = std::max(squared_radius, glm::dot(d, d));
    }
    middles.push_back(middle - centre);
    radii.push_back(std::sqrt(squared_radius));
  }
  ball.cull = TriangleCull(middles, radii);
  for (std::size_t e = 0; e < ball.mesh_edge.size(); ++e) {
    const auto& ends = mesh.edges[ball.mesh_edge[e]];
    ball.ends[e] = {local_vertex[ends[0]], local_vertex[ends[1]]};
  }
  ball.rim.resize(ball.mesh_edge.size());
  for (std::size_t e = 0; e < ball.mesh_edge.size(); ++e) ball.rim[e] = mesh.edge_triangles[ball.mesh_edge[e]][1] < 0;
  return ball;
}

struct Segment {
  std::uint32_t from_edge = 0;  // ball edges: where the section leaves the triangle's positive side
  std::uint32_t to_edge = 0;
  Vec3 from{0.0};
  Vec3 to{0.0};
};

// One plane's section of the ball, with the scratch arrays every plane reuses.
class Sectioner {
 public:
  Sectioner(const Vec3& centre, Ball ball)
      : centre_(centre), ball_(std::move(ball)), parent_(ball_.mesh_edge.size()),
        ends_(ball_.mesh_edge.size(), 0), loop_of_(ball_.mesh_edge.size(), -1) {
    for (std::uint32_t e = 0; e < parent_.size(); ++e) parent_[e] = e;
  }

  bool empty() const { return ball_.corners.empty(); }

  // The length of the shortest closed loop around the centre in the plane through it with this
  // normal (unit), or infinity. Its mesh edges go to `loop_edges` if given.
  double girth(const Vec3& normal, std::vector<std::uint32_t>* loop_edges = nullptr) {
    normal_ = normal;
    cut();
    std::vector<Loop> loops;
    for (const Segment& s : segments_) {
      const std::uint32_t root = find(s.from_edge);
      if (loop_of_[root] < 0) {
        loop_of_[root] = static_cast<std::int32_t>(loops.size());
        loops.push_back(Loop{});
        roots_.push_back(root);
      }
      Loop& loop = loops[static_cast<std::size_t>(loop_of_[root])];
      loop.length += glm::length(s.to - s.from);
      // A closed loop crosses each of its edges from both triangles; an edge crossed once is where
      // the section leaves the ball's triangles.
      loop.open = loop.open || ends_[s.from_edge] != 2 || ends_[s.to_edge] != 2;
    }
    // Which loops go round the centre: those a ray from it (along u, in the plane) crosses an odd
    // number of times. Parity, not a winding number, so the triangles' orientation does not matter.
    const auto [u, w] = squareTo(normal);
    for (const Segment& s : segments_) {
      Loop& loop = loops[static_cast<std::size_t>(loop_of_[find(s.from_edge)])];
      if (loop.open) continue;
      const double ya = glm::dot(w, s.from - centre_);
      const double yb = glm::dot(w, s.to - centre_);
      if ((ya >= 0.0) == (yb >= 0.0)) continue;
      const double xa = glm::dot(u, s.from - centre_);
      const double xb = glm::dot(u, s.to - centre_);
      if (xa + (xb - xa) * (ya / (ya - yb)) > 0.0) loop.around = !loop.around;
    }
    // The centre is inside the section where an odd number of loops go round it; an even number (a
    // ring's two rims, with the centre in its hole) is no cross-section of the body.
    double best = std::numeric_limits<double>::infinity();
    std::int32_t best_loop = -1;
    std::size_t around = 0;
    for (std::size_t l = 0; l < loops.size(); ++l) {
      if (loops[l].open || !loops[l].around) continue;
      ++around;
      if (!(loops[l].length < best)) continue;
      best = loops[l].length;
      best_loop = static_cast<std::int32_t>(l);
    }
    if (around % 2 == 0) {
      best = std::numeric_limits<double>::infinity();
      best_loop = -1;
    }
    if (loop_edges != nullptr && best_loop >= 0) {
      for (const Segment& s : segments_) {
        if (loop_of_[find(s.from_edge)] == best_loop) loop_edges->push_back(ball_.mesh_edge[s.from_edge]);
      }
    }
    reset();
    return best;
  }

 private:
  struct Loop {
    double length = 0.0;
    bool around = false;
    bool open = false;
  };

  // The segments of the section, and the loops they form (union-find over the crossed edges). A
  // triangle whose segment ends on a hole's rim, or on a fin hung on an edge of the surface,
  // adds a dangling piece, not part of a loop around the body: left out.
  void cut() {
    segments_.clear();
    ball_.cull.nearPlane(normal_, near_);
    for (const std::uint32_t t : near_) {
      const auto& corners = ball_.corners[t];
      const std::array<bool, 3> up{side(corners[0]) >= 0.0, side(corners[1]) >= 0.0, side(corners[2]) >= 0.0};
      if (up[0] == up[1] && up[1] == up[2]) continue;
      Segment segment;
      for (std::size_t k = 0; k < 3; ++k) {
        const std::size_t next = (k + 1) % 3;
        if (up[k] == up[next]) continue;
        const std::uint32_t e = ball_.edges[t][k];
        if (up[k]) {
          segment.from_edge = e;
          segment.from = crossing(e);
        } else {
          segment.to_edge = e;
          segment.to = crossing(e);
        }
      }
      if (ball_.rim[segment.from_edge] || ball_.rim[segment.to_edge]) continue;
      join(segment.from_edge, segment.to_edge);
      ++ends_[segment.from_edge];
      ++ends_[segment.to_edge];
      segments_.push_back(segment);
    }
  }

  // Where the plane crosses a ball edge, computed from the edge's own ends in the mesh's order, so
  // that its two triangles get the same point bit for bit (the ray's crossing count relies on it).
  Vec3 crossing(std::uint32_t e) const {
    const auto [a, b] = ball_.ends[e];
    const double sa = side(a);
    const double sb = side(b);
    return glm::mix(ball_.positions[a], ball_.positions[b], sa / (sa - sb));
  }

  // The signed distance of a ball vertex to the plane, the same number wherever it is asked for.
  double side(std::uint32_t v) const { return glm::dot(normal_, ball_.positions[v] - centre_); }

  std::uint32_t find(std::uint32_t e) {
    while (parent_[e] != e) {
      parent_[e] = parent_[parent_[e]];
      e = parent_[e];
    }
    return e;
  }
  void join(std::uint32_t a, std::uint32_t b) {
    touched_.push_back(a);
    touched_.push_back(b);
    a = find(a);
    b = find(b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);
  }
  void reset() {
    for (const std::uint32_t e : touched_) {
      parent_[e] = e;
      ends_[e] = 0;
    }
    for (const std::uint32_t r : roots_) loop_of_[r] = -1;
    touched_.clear();
    roots_.clear();
  }

  Vec3 centre_;
  Ball ball_;
  Vec3 normal_{0.0};
  std::vector<std::uint32_t> near_;  // the triangles the plane may cut
  std::vector<std::uint32_t> parent_;
  std::vector<std::uint32_t> ends_;    // per edge: segments ending on it this plane
  std::vector<std::int32_t> loop_of_;  // per root edge: its loop this plane, -1 none
  std::vector<std::uint32_t> touched_;
  std::vector<std::uint32_t> roots_;
  std::vector<Segment> segments_;
};

}  // namespace

std::array<Vec3, 2> squareTo(const Vec3& n) {
  const Vec3 helper = std::abs(n.x) < 0.6 ? Vec3(1.0, 0.0, 0.0) : Vec3(0.0, 1.0, 0.0);
  const Vec3 u = glm::normalize(glm::cross(n, helper));
  return {u, glm::cross(n, u)};
}

std::optional<GirthPlane> leastGirthPlane(std::span<const Vec3> positions, const MeshTopology& mesh, const Vec3& centre,
                                          double reach, std::span<const Vec3> starts, std::span<const char> include) {
  Sectioner sectioner(centre, ballAround(positions, mesh, centre, reach, include));
  if (sectioner.empty()) return std::nullopt;

  Vec3 best_normal{0.0};
  double best = std::numeric_limits<double>::infinity();
  auto consider = [&](const Vec3& n) {
    const double g = sectioner.girth(n);
    if (g >= best) return false;
    best = g;
    best_normal = n;
    return true;
  };
  for (const Vec3& start : starts) {
    if (glm::length(start) > 0.0) consider(glm::normalize(start));
  }
  if (!std::isfinite(best)) return std::nullopt;
  double step = kFirstStep;
  for (int round = 0; round < kRefineRounds; ++round, step *= 0.5) {
    for (int move = 0; move < kMovesPerStep; ++move) {
      const Vec3 from = best_normal;
      const auto [u, w] = squareTo(from);
      bool moved = false;
      for (int k = 0; k < kRefineNeighbours; ++k) {
        const double angle = 2.0 * std::numbers::pi * k / kRefineNeighbours;
        moved |= consider(glm::normalize(from + step * (std::cos(angle) * u + std::sin(angle) * w)));
      }
      if (!moved) break;
    }
  }
  GirthPlane plane;
  plane.normal = best_normal;
  std::vector<std::uint32_t> edges;
  plane.girth = sectioner.girth(best_normal, &edges);
  for (const std::uint32_t e : edges) {
    plane.vertices.push_back(mesh.edges[e][0]);
    plane.vertices.push_back(mesh.edges[e][1]);
  }
  std::sort(plane.vertices.begin(), plane.vertices.end());
  plane.vertices.erase(std::unique(plane.vertices.begin(), plane.vertices.end()), plane.vertices.end());
  for (const std::uint32_t v : plane.vertices) {
    plane.distances.push_back(std::abs(glm::dot(best_normal, positions[v] - centre)));
  }
  return plane;
}

}  // namespace odeskin
