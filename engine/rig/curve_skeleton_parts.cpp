// SPDX-License-Identifier: MIT
#include "curve_skeleton_parts.hpp"

#include <algorithm>
#include <array>

#include <glm/geometric.hpp>

namespace odeskin {

TreeParts treeParts(const LevelGraph& graph, const LevelTree& tree) {
  TreeParts out;
  out.contour_part.assign(graph.contours.size(), -1);
  out.region_part.assign(graph.regions.size(), -1);
  std::vector<std::uint32_t> order{tree.root};
  for (std::size_t head = 0; head < order.size(); ++head) {
    const std::uint32_t r = order[head];
    const bool branching = r == tree.root || tree.children[r].size() >= 2;
    for (const std::uint32_t c : tree.children[r]) {
      std::int32_t part = out.region_part[r];
      if (branching) {
        part = static_cast<std::int32_t>(out.parts.size());
        TreePart p;
        p.start_region = r;
        p.parent = out.region_part[r];
        p.depth = p.parent >= 0 ? out.parts[static_cast<std::size_t>(p.parent)].depth + 1 : 0;
        out.parts.push_back(p);
        if (r == tree.root && out.region_part[r] < 0) out.region_part[r] = part;
      }
      const auto q = static_cast<std::uint32_t>(tree.child_region[c]);
      out.contour_part[c] = part;
      out.region_part[q] = part;
      out.parts[static_cast<std::size_t>(part)].end_region = static_cast<std::int32_t>(q);
      order.push_back(q);
    }
  }
  if (out.parts.empty()) {  // a tree of one region: one part
    out.parts.push_back(TreePart{tree.root, -1, -1, 0});
    out.region_part[tree.root] = 0;
  }
  for (std::uint32_t r = 0; r < graph.regions.size(); ++r) {
    if (tree.reached[r] && out.region_part[r] < 0) out.region_part[r] = out.region_part[tree.owner[r]];
  }
  out.vertex_parts.assign(graph.vertex_region.size(), 0);
  for (std::size_t v = 0; v < graph.vertex_region.size(); ++v) {
    const std::uint32_t r = graph.vertex_region[v];
    if (r != LevelGraph::kNoRegion && out.region_part[r] >= 0) out.vertex_parts[v] = static_cast<std::uint32_t>(out.region_part[r]);
  }
  return out;
}

SkeletonNodeKind regionKind(const LevelTree& tree, std::uint32_t region, bool* has_node) {
  *has_node = true;
  if (region == tree.root) return SkeletonNodeKind::kRoot;
  if (tree.children[region].empty()) return SkeletonNodeKind::kTip;
  if (tree.children[region].size() >= 2) return SkeletonNodeKind::kJunction;
  *has_node = false;
  return SkeletonNodeKind::kCurve;
}

namespace {

// The node's fields beside its anchors, which the caller has appended to s.anchors.
void appendNode(CurveSkeleton& s, SkeletonNodeKind kind, std::int32_t parent, std::uint32_t part, double radius,
                const Vec3& position) {
  s.positions.push_back(position);
  s.radii.push_back(radius);
  s.kinds.push_back(kind);
  s.parents.push_back(parent);
  s.parts.push_back(part);
  s.anchor_offsets.push_back(static_cast<std::uint32_t>(s.anchors.size()));
}

}  // namespace

void addSkeletonNode(CurveSkeleton& s, SkeletonNodeKind kind, std::int32_t parent, std::uint32_t part, double radius,
                     std::span<const SkeletonAnchor> anchors, std::span<const Vec3> rest) {
  Vec3 sum(0.0);
  double total = 0.0;
  for (const SkeletonAnchor& a : anchors) {
    sum += a.weight * curvePointPosition(rest, a.point);
    total += a.weight;
  }
  s.anchors.insert(s.anchors.end(), anchors.begin(), anchors.end());
  appendNode(s, kind, parent, part, radius, total > 0.0 ? sum / total : sum);
}

void addCurveNode(CurveSkeleton& s, SkeletonNodeKind kind, std::int32_t parent, std::uint32_t part, double radius,
                  std::span<const CurvePoint> points, bool closed, std::span<const Vec3> rest) {
  // One pass: the anchors go straight into the skeleton with their final weights, each point's
  // position computed once. A point's weight is half of each segment it ends (0 for a missing
  // one, at the ends of an open curve). Adding the two halves in either order gives the same
  // number, so the closing segment of a closed curve, which point 0 needs first, is measured up front.
  const std::size_t n = points.size();
  if (n == 0) {
    appendNode(s, kind, parent, part, radius, Vec3(0.0));
    return;
  }
  const std::size_t first = s.anchors.size();
  const Vec3 first_at = curvePointPosition(rest, points[0]);
  const double closing = closed && n > 1 ? 0.5 * glm::length(first_at - curvePointPosition(rest, points[n - 1])) : 0.0;
  Vec3 sum(0.0);
  double total = 0.0;
  Vec3 at = first_at;
  double before = closing;  // half the segment that ends at point i
  for (std::size_t i = 0; i < n; ++i) {
    const bool last = i + 1 == n;
    const Vec3 next = last ? first_at : curvePointPosition(rest, points[i + 1]);
    const double after = last ? closing : 0.5 * glm::length(next - at);
    const double weight = before + after;
    s.anchors.push_back({points[i], weight});
    sum += weight * at;
    total += weight;
    before = after;
    at = next;
  }
  if (!(total > 0.0)) {  // no length: every point counts once
    sum = Vec3(0.0);
    total = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      s.anchors[first + i].weight = 1.0;
      sum += curvePointPosition(rest, points[i]);
      total += 1.0;
    }
  }
  appendNode(s, kind, parent, part, radius, sum / total);
}

std::vector<SkeletonAnchor> regionAnchors(const LevelGraph& graph, std::uint32_t region) {
  std::vector<SkeletonAnchor> anchors;
  for (const std::uint32_t v : graph.regions[region].vertices) anchors.push_back({CurvePoint{v, v, 0.0}, 1.0});
  return anchors;
}

std::vector<SkeletonAnchor> tipAnchors(const LevelGraph& graph, std::uint32_t region, const MeshTopology& mesh) {
  std::vector<std::uint32_t> rim;
  for (const std::uint32_t v : graph.regions[region].vertices) {
    if (mesh.boundary_vertex[v]) rim.push_back(v);
  }
  if (rim.empty()) return regionAnchors(graph, region);
  // Along boundary edges to the rest of the loop(s).
  std::vector<char> seen(mesh.boundary_vertex.size(), 0);
  for (const std::uint32_t v : rim) seen[v] = 1;
  for (std::size_t head = 0; head < rim.size(); ++head) {
    const std::uint32_t u = rim[head];
    for (std::uint32_t k = mesh.vertex_offsets[u]; k < mesh.vertex_offsets[u + 1]; ++k) {
      const std::uint32_t e = mesh.vertex_edges[k];
      if (mesh.edge_triangles[e][1] >= 0) continue;
      const std::uint32_t w = mesh.edges[e][0] == u ? mesh.edges[e][1] : mesh.edges[e][0];
      if (!seen[w]) {
        seen[w] = 1;
        rim.push_back(w);
      }
    }
  }
  std::vector<SkeletonAnchor> anchors;
  anchors.reserve(rim.size());
  for (const std::uint32_t v : rim) anchors.push_back({CurvePoint{v, v, 0.0}, 1.0});
  return anchors;
}

namespace {

// The walk of a contour with a point on three or more segments: a level through an edge of
// three or more triangles (a non-manifold mesh). Each point keeps its first and its last
// neighbour, an open contour starts at its first point with fewer than two, and the walk stops at
// a point already taken.
IsoCurve walkBranchingContour(const LevelContour& contour, std::uint32_t part) {
  const std::size_t n = contour.points.size();
  std::vector<std::array<std::int32_t, 2>> next(n, {-1, -1});
  for (const auto& s : contour.segments) {
    for (int side = 0; side < 2; ++side) {
      auto& slot = next[s[static_cast<std::size_t>(side)]];
      (slot[0] < 0 ? slot[0] : slot[1]) = static_cast<std::int32_t>(s[static_cast<std::size_t>(1 - side)]);
    }
  }
  std::size_t start = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (next[i][1] < 0) {
      start = i;
      break;
    }
  }
  IsoCurve curve;
  curve.closed = contour.closed;
  curve.part = part;
  curve.points.reserve(n);
  std::vector<char> seen(n, 0);
  std::int32_t previous = -1;
  for (auto at = static_cast<std::int32_t>(start); at >= 0 && !seen[static_cast<std::size_t>(at)];) {
    const auto i = static_cast<std::size_t>(at);
    seen[i] = 1;
    curve.points.push_back(contour.points[i]);
    const std::int32_t step = next[i][0] != previous ? next[i][0] : next[i][1];
    previous = at;
    at = step;
  }
  return curve;
}

}  // namespace

IsoCurve orderedContour(const LevelContour& contour, std::uint32_t part) {
  // Where every point ends at most two segments (a crossing lies on one edge, in at most two
  // triangles of a manifold mesh), the contour is one path or one cycle. Each point keeps its
  // neighbours XORed (numbered from 1, 0 for none) and their count: the walk's next point is the
  // link XOR the one it came from, without the branch on which neighbour that was (a coin toss
  // for the predictor) and without visited flags. The same walk as walkBranchingContour's there.
  const std::size_t n = contour.points.size();
  std::vector<std::uint32_t> links(n, 0);
  std::vector<std::uint32_t> degree(n, 0);
  for (const auto& s : contour.segments) {
    links[s[0]] ^= s[1] + 1;
    links[s[1]] ^= s[0] + 1;
    ++degree[s[0]];
    ++degree[s[1]];
  }
  std::uint32_t most = 0;
  for (const std::uint32_t d : degree) most = std::max(most, d);
  if (most > 2) return walkBranchingContour(contour, part);
  // An open contour starts at its first end; a closed one at point 0, towards its first segment's other point.
  std::size_t start = 0;
  while (start < n && degree[start] >= 2) ++start;
  IsoCurve curve;
  curve.closed = contour.closed;
  curve.part = part;
  curve.points.reserve(n);
  if (n == 0) return curve;
  std::uint32_t from = 0;  // the previous point + 1
  if (start == n) {
    start = 0;
    for (const auto& s : contour.segments) {
      if (s[0] == 0 || s[1] == 0) {
        from = links[0] ^ ((s[0] == 0 ? s[1] : s[0]) + 1);
        break;
      }
    }
  }
  auto at = static_cast<std::uint32_t>(start);
  for (std::size_t k = 0; k < n; ++k) {
    curve.points.push_back(contour.points[at]);
    const std::uint32_t next = links[at] ^ from;
    from = at + 1;
    if (next == 0 || next - 1 == start) break;
    at = next - 1;
  }
  return curve;
}

}  // namespace odeskin
