// SPDX-License-Identifier: MIT
#include "curve_skeleton_levels.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>
#include "../core/disjoint_sets.hpp"
#include "../core/parallel.hpp"

namespace odeskin {
namespace {

// The slab of a value (values are >= 0 and finite here).
std::uint32_t slabOf(double value, double spacing) { return static_cast<std::uint32_t>(std::floor(value / spacing)); }

// The length-weighted centroid from the contour's points already placed (point(i): point i); the
// contour's length (the same sum, in the same order) into `length` if given.
template <typename Point>
Vec3 centroidOf(const LevelContour& contour, const Point& point, double* length = nullptr) {
  Vec3 sum(0.0);
  double total = 0.0;
  for (const auto& s : contour.segments) {
    const Vec3 a = point(s[0]);
    const Vec3 b = point(s[1]);
    const double segment = glm::length(b - a);
    sum += 0.5 * segment * (a + b);
    total += segment;
  }
  if (length != nullptr) *length = total;
  if (total > 0.0) return sum / total;
  Vec3 mean(0.0);
  for (std::size_t i = 0; i < contour.points.size(); ++i) mean += point(static_cast<std::uint32_t>(i));
  return contour.points.empty() ? mean : mean / static_cast<double>(contour.points.size());
}

constexpr std::uint32_t kUnreachedSlab = std::numeric_limits<std::uint32_t>::max();
// From this many triangles on, the regions and the contours of a level graph are found on two
// threads at once (below it the hand-over costs more than it saves).
constexpr std::size_t kParallelTriangles = 2048;

// What both halves of the level graph read. Triangle t owns one piece per slab in [lo[t], lo[t] +
// base[t + 1] - base[t]) (none with a corner unreached); edge e crosses level s (f = s * spacing)
// for s in (edge_lo[e], edge_lo[e] + its crossing count], its crossings numbered from
// crossing_base[e].
struct SlabLayout {
  std::vector<std::uint32_t> vertex_slab;  // kUnreachedSlab where f is infinite
  std::vector<std::uint32_t> lo, base;
  std::vector<std::uint32_t> edge_lo, crossing_base;

  bool reached(std::uint32_t t) const { return base[t + 1] != base[t]; }
  std::uint32_t piece(std::uint32_t t, std::uint32_t slab) const { return base[t] + slab - lo[t]; }
  std::uint32_t crossings(std::uint32_t e) const { return crossing_base[e + 1] - crossing_base[e]; }
  std::uint32_t crossing(std::uint32_t e, std::uint32_t s) const { return crossing_base[e] + s - edge_lo[e] - 1; }
  bool crosses(std::uint32_t e, std::uint32_t s) const { return s > edge_lo[e] && s <= edge_lo[e] + crossings(e); }
};

SlabLayout slabLayout(const MeshTopology& mesh, std::span<const double> f, double spacing) {
  SlabLayout layout;
  const std::size_t t_count = mesh.triangles.size();
  const std::size_t e_count = mesh.edges.size();
  layout.vertex_slab.resize(f.size());
  for (std::size_t v = 0; v < f.size(); ++v) layout.vertex_slab[v] = std::isfinite(f[v]) ? slabOf(f[v], spacing) : kUnreachedSlab;
  const std::vector<std::uint32_t>& slab = layout.vertex_slab;
  layout.lo.assign(t_count, 0);
  layout.base.assign(t_count + 1, 0);
  for (std::uint32_t t = 0; t < t_count; ++t) {
    const auto& tri = mesh.triangles[t];
    const std::uint32_t a = slab[tri[0]], b = slab[tri[1]], c = slab[tri[2]];
    std::uint32_t count = 0;
    if (a != kUnreachedSlab && b != kUnreachedSlab && c != kUnreachedSlab) {
      layout.lo[t] = std::min({a, b, c});
      count = std::max({a, b, c}) - layout.lo[t] + 1;
    }
    layout.base[t + 1] = layout.base[t] + count;
  }
  layout.edge_lo.assign(e_count, 0);
  layout.crossing_base.assign(e_count + 1, 0);
  for (std::size_t e = 0; e < e_count; ++e) {
    const std::uint32_t su = slab[mesh.edges[e][0]];
    const std::uint32_t sv = slab[mesh.edges[e][1]];
    std::uint32_t count = 0;
    if (su != kUnreachedSlab && sv != kUnreachedSlab) {
      layout.edge_lo[e] = std::min(su, sv);
      count = std::max(su, sv) - layout.edge_lo[e];
    }
    layout.crossing_base[e + 1] = layout.crossing_base[e] + count;
  }
  return layout;
}

// The regions: the triangles' pieces of a slab joined where their shared edge meets the slab,
// numbered in the order the triangles first meet them (pieces, then corners). Fills the graph's
// regions (slab, vertices) and vertex_region; `pieces` is left flattened and `region_of_root` maps
// its roots to regions.
void findRegions(const MeshTopology& mesh, const SlabLayout& layout, LevelGraph& graph, DisjointSets& pieces,
                 std::vector<std::uint32_t>& region_of_root) {
  const std::size_t t_count = mesh.triangles.size();
  for (std::uint32_t e = 0; e < mesh.edges.size(); ++e) {
    // Both triangles reached: so are the edge's ends, and its slab range is [edge_lo, + crossings].
    const auto [t0, t1] = mesh.edge_triangles[e];
    if (t1 < 0 || !layout.reached(static_cast<std::uint32_t>(t0)) || !layout.reached(static_cast<std::uint32_t>(t1))) continue;
    const auto a = static_cast<std::uint32_t>(t0);
    const auto b = static_cast<std::uint32_t>(t1);
    const std::uint32_t hi = layout.edge_lo[e] + layout.crossings(e);
    for (std::uint32_t s = layout.edge_lo[e]; s <= hi; ++s) pieces.unite(layout.piece(a, s), layout.piece(b, s));
  }
  pieces.flatten();
  region_of_root.assign(layout.base[t_count], LevelGraph::kNoRegion);
  for (std::uint32_t t = 0; t < t_count; ++t) {
    for (std::uint32_t p = layout.base[t]; p < layout.base[t + 1]; ++p) {
      std::uint32_t& region = region_of_root[pieces.parent[p]];
      if (region == LevelGraph::kNoRegion) {
        region = static_cast<std::uint32_t>(graph.regions.size());
        graph.regions.emplace_back().slab = layout.lo[t] + p - layout.base[t];
      }
    }
    if (!layout.reached(t)) continue;
    for (const std::uint32_t v : mesh.triangles[t]) {
      if (graph.vertex_region[v] == LevelGraph::kNoRegion) {
        graph.vertex_region[v] = region_of_root[pieces.parent[layout.piece(t, layout.vertex_slab[v])]];
      }
    }
  }
  std::vector<std::uint32_t> sizes(graph.regions.size(), 0);
  for (const std::uint32_t r : graph.vertex_region) {
    if (r != LevelGraph::kNoRegion) ++sizes[r];
  }
  for (std::size_t r = 0; r < sizes.size(); ++r) graph.regions[r].vertices.reserve(sizes[r]);
  for (std::uint32_t v = 0; v < graph.vertex_region.size(); ++v) {
    if (graph.vertex_region[v] != LevelGraph::kNoRegion) graph.regions[graph.vertex_region[v]].vertices.push_back(v);
  }
}

// The contours: one segment per level strictly inside a reached triangle's slab range, between
// the crossings of that level on two of its edges; segments sharing a crossing form a contour,
// numbered in the order the segments first meet them. Fills the graph's contours (all but lower
// and upper) and each contour's first segment's triangle, which decides them.
void findContours(std::span<const Vec3> positions, const MeshTopology& mesh, std::span<const double> f, double spacing,
                  const SlabLayout& layout, LevelGraph& graph, std::vector<std::uint32_t>& first_triangle) {
  const std::size_t t_count = mesh.triangles.size();
  const std::uint32_t crossing_count = layout.crossing_base.back();
  struct Segment {
    std::uint32_t e0, e1, triangle, level;
  };
  std::vector<Segment> segments;
  DisjointSets links(crossing_count);
  for (std::uint32_t t = 0; t < t_count; ++t) {
    if (layout.base[t + 1] - layout.base[t] < 2) continue;
    const std::uint32_t hi = layout.lo[t] + (layout.base[t + 1] - layout.base[t]) - 1;
    for (std::uint32_t s = layout.lo[t] + 1; s <= hi; ++s) {
      std::uint32_t found[2] = {0, 0};
      int n = 0;
      for (const std::uint32_t e : mesh.triangle_edges[t]) {
        if (layout.crosses(e, s) && n < 2) found[n++] = e;
      }
      assert(n == 2);
      links.unite(layout.crossing(found[0], s), layout.crossing(found[1], s));
      segments.push_back({found[0], found[1], t, s});
    }
  }
  links.flatten();

  // Contours' sizes are counted before they are filled.
  std::vector<std::uint32_t> contour_of_root(crossing_count, LevelGraph::kNoRegion);
  std::vector<std::uint32_t> segment_counts;
  for (const Segment& seg : segments) {
    const std::uint32_t root = links.parent[layout.crossing(seg.e0, seg.level)];
    if (contour_of_root[root] == LevelGraph::kNoRegion) {
      contour_of_root[root] = static_cast<std::uint32_t>(graph.contours.size());
      graph.contours.emplace_back().level = seg.level;
      first_triangle.push_back(seg.triangle);
      segment_counts.push_back(0);
    }
    ++segment_counts[contour_of_root[root]];
  }
  {
    std::vector<std::uint32_t> point_counts(graph.contours.size(), 0);
    for (std::uint32_t c = 0; c < crossing_count; ++c) {
      const std::uint32_t contour = contour_of_root[links.parent[c]];
      if (contour != LevelGraph::kNoRegion) ++point_counts[contour];
    }
    for (std::size_t c = 0; c < graph.contours.size(); ++c) {
      graph.contours[c].points.reserve(point_counts[c]);
      graph.contours[c].segments.reserve(segment_counts[c]);
    }
  }
  std::vector<std::uint32_t> point_of_crossing(crossing_count, LevelGraph::kNoRegion);
  std::vector<std::uint32_t> uses(crossing_count, 0);
  auto pointOf = [&](LevelContour& contour, std::uint32_t e, std::uint32_t s) {
    const std::uint32_t c = layout.crossing(e, s);
    if (point_of_crossing[c] == LevelGraph::kNoRegion) {
      std::uint32_t a = mesh.edges[e][0];
      std::uint32_t b = mesh.edges[e][1];
      if (f[a] > f[b]) std::swap(a, b);
      const double level = spacing * static_cast<double>(s);
      const double t = f[b] > f[a] ? std::clamp((level - f[a]) / (f[b] - f[a]), 0.0, 1.0) : 0.0;
      point_of_crossing[c] = static_cast<std::uint32_t>(contour.points.size());
      contour.points.push_back({a, b, t});
    }
    ++uses[c];
    return point_of_crossing[c];
  };
  for (const Segment& seg : segments) {
    LevelContour& contour = graph.contours[contour_of_root[links.parent[layout.crossing(seg.e0, seg.level)]]];
    const std::uint32_t p0 = pointOf(contour, seg.e0, seg.level);
    const std::uint32_t p1 = pointOf(contour, seg.e1, seg.level);
    contour.segments.push_back({p0, p1});
  }
  for (std::uint32_t c = 0; c < crossing_count; ++c) {
    if (uses[c] == 1) graph.contours[contour_of_root[links.parent[c]]].closed = false;
  }
  std::vector<Vec3> at;  // a contour's points on `positions`, computed once for its sums
  for (LevelContour& contour : graph.contours) {
    at.clear();
    for (const CurvePoint& p : contour.points) at.push_back(curvePointPosition(positions, p));
    contour.centroid = centroidOf(contour, [&](std::uint32_t i) { return at[i]; }, &contour.length);
    double radius = 0.0;
    for (const Vec3& p : at) radius += glm::length(p - contour.centroid);
    contour.radius = contour.points.empty() ? 0.0 : radius / static_cast<double>(contour.points.size());
  }
}

}  // namespace

LevelGraph levelGraph(std::span<const Vec3> positions, const MeshTopology& mesh, std::span<const double> f,
                      double spacing) {
  assert(spacing > 0.0);
  LevelGraph graph;
  graph.spacing = spacing;
  graph.vertex_region.assign(positions.size(), LevelGraph::kNoRegion);
  const SlabLayout layout = slabLayout(mesh, f, spacing);
  // The regions and the contours need each other only for the contours' two region numbers, so
  // on a large mesh they are found at the same time (each writes its own part of the graph).
  DisjointSets pieces(layout.base.back());
  std::vector<std::uint32_t> region_of_root;
  std::vector<std::uint32_t> first_triangle;
  auto regions = [&] { findRegions(mesh, layout, graph, pieces, region_of_root); };
  auto contours = [&] { findContours(positions, mesh, f, spacing, layout, graph, first_triangle); };
  if (mesh.triangles.size() >= kParallelTriangles) {
    parallelInvoke(regions, contours);
  } else {
    regions();
    contours();
  }
  auto regionOf = [&](std::uint32_t t, std::uint32_t slab) { return region_of_root[pieces.parent[layout.piece(t, slab)]]; };
  std::vector<std::uint32_t> sizes(graph.regions.size(), 0);
  for (std::uint32_t c = 0; c < graph.contours.size(); ++c) {
    LevelContour& contour = graph.contours[c];
    contour.lower = regionOf(first_triangle[c], contour.level - 1);
    contour.upper = regionOf(first_triangle[c], contour.level);
    ++sizes[contour.lower];
    ++sizes[contour.upper];
  }
  for (std::size_t r = 0; r < sizes.size(); ++r) graph.regions[r].contours.reserve(sizes[r]);
  for (std::uint32_t c = 0; c < graph.contours.size(); ++c) {
    graph.regions[graph.contours[c].lower].contours.push_back(c);
    graph.regions[graph.contours[c].upper].contours.push_back(c);
  }
  for (LevelRegion& region : graph.regions) {
    Vec3 sum(0.0);
    if (!region.vertices.empty()) {
      for (const std::uint32_t v : region.vertices) sum += positions[v];
      region.centroid = sum / static_cast<double>(region.vertices.size());
    } else if (!region.contours.empty()) {
      for (const std::uint32_t c : region.contours) sum += graph.contours[c].centroid;
      region.centroid = sum / static_cast<double>(region.contours.size());
    }
  }
  return graph;
}

Vec3 contourCentroid(const LevelContour& contour, std::span<const Vec3> positions) {
  return centroidOf(contour, [&](std::uint32_t i) { return curvePointPosition(positions, contour.points[i]); });
}

}  // namespace odeskin
