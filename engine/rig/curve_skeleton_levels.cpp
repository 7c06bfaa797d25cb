// SPDX-License-Identifier: MIT
#include "curve_skeleton_levels.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numeric>
#include <functional>
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

}  // namespace

MeshTopology meshTopology(std::span<const Vec3> positions, const FaceList& faces) {
  MeshTopology mesh;
  const std::size_t v_count = positions.size();
  for (std::size_t f = 0; f < faces.faceCount(); ++f) {
    const std::uint32_t begin = faces.face_offsets[f];
    const std::uint32_t end = faces.face_offsets[f + 1];
    for (std::uint32_t k = begin + 1; k + 1 < end; ++k) {
      mesh.triangles.push_back({faces.indices[begin], faces.indices[k], faces.indices[k + 1]});
    }
  }
  // Half-edges bucketed by their smaller vertex (a counting sort), then matched within a bucket.
  // Each is kept as one key, its larger vertex above its index 3 t + k: sorting a bucket's keys
  // orders its half-edges by their other end, then by index.
  const std::size_t h_count = 3 * mesh.triangles.size();
  std::vector<std::uint32_t> bucket(v_count + 1, 0);
  for (const auto& t : mesh.triangles) {
    for (std::uint32_t k = 0; k < 3; ++k) ++bucket[std::min(t[k], t[(k + 1) % 3]) + 1];
  }
  for (std::size_t v = 0; v < v_count; ++v) bucket[v + 1] += bucket[v];
  std::vector<std::uint64_t> half(h_count);
  {
    std::vector<std::uint32_t> fill(bucket.begin(), bucket.end() - 1);
    for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) {
      for (std::uint32_t k = 0; k < 3; ++k) {
        const std::uint32_t a = mesh.triangles[t][k];
        const std::uint32_t b = mesh.triangles[t][(k + 1) % 3];
        half[fill[std::min(a, b)]++] = static_cast<std::uint64_t>(std::max(a, b)) << 32 | (3 * t + k);
      }
    }
  }
  auto other = [](std::uint64_t key) { return static_cast<std::uint32_t>(key >> 32); };
  auto triangle = [](std::uint64_t key) { return static_cast<std::uint32_t>(key) / 3; };
  auto side = [](std::uint64_t key) { return static_cast<std::uint32_t>(key) % 3; };
  mesh.triangle_edges.resize(mesh.triangles.size());
  mesh.edges.reserve(h_count / 2);  // exact for a closed manifold mesh
  mesh.edge_triangles.reserve(h_count / 2);
  for (std::uint32_t v = 0; v < v_count; ++v) {
    std::sort(half.begin() + bucket[v], half.begin() + bucket[v + 1]);
    for (std::uint32_t i = bucket[v]; i < bucket[v + 1];) {
      const auto e = static_cast<std::uint32_t>(mesh.edges.size());
      const std::uint32_t w = other(half[i]);
      mesh.edges.push_back({v, w});
      mesh.edge_triangles.push_back({static_cast<std::int32_t>(triangle(half[i])), -1});
      std::uint32_t j = i;
      for (; j < bucket[v + 1] && other(half[j]) == w; ++j) {
        mesh.triangle_edges[triangle(half[j])][side(half[j])] = e;
        if (j == i + 1) mesh.edge_triangles.back()[1] = static_cast<std::int32_t>(triangle(half[j]));
      }
      i = j;
    }
  }
  mesh.edge_lengths.resize(mesh.edges.size());
  mesh.vertex_offsets.assign(v_count + 1, 0);
  for (std::size_t e = 0; e < mesh.edges.size(); ++e) {
    mesh.edge_lengths[e] = glm::length(positions[mesh.edges[e][1]] - positions[mesh.edges[e][0]]);
    ++mesh.vertex_offsets[mesh.edges[e][0] + 1];
    ++mesh.vertex_offsets[mesh.edges[e][1] + 1];
  }
  for (std::size_t v = 0; v < v_count; ++v) mesh.vertex_offsets[v + 1] += mesh.vertex_offsets[v];
  mesh.vertex_edges.resize(2 * mesh.edges.size());
  mesh.vertex_neighbours.resize(2 * mesh.edges.size());
  mesh.vertex_edge_lengths.resize(2 * mesh.edges.size());
  std::vector<std::uint32_t> fill(mesh.vertex_offsets.begin(), mesh.vertex_offsets.end() - 1);
  for (std::uint32_t e = 0; e < mesh.edges.size(); ++e) {
    for (int end = 0; end < 2; ++end) {
      const std::uint32_t k = fill[mesh.edges[e][static_cast<std::size_t>(end)]]++;
      mesh.vertex_edges[k] = e;
      mesh.vertex_neighbours[k] = mesh.edges[e][static_cast<std::size_t>(1 - end)];
      mesh.vertex_edge_lengths[k] = mesh.edge_lengths[e];
    }
  }
  mesh.vertex_triangle_offsets.assign(v_count + 1, 0);
  for (const auto& t : mesh.triangles) {
    for (const std::uint32_t v : t) ++mesh.vertex_triangle_offsets[v + 1];
  }
  for (std::size_t v = 0; v < v_count; ++v) mesh.vertex_triangle_offsets[v + 1] += mesh.vertex_triangle_offsets[v];
  mesh.vertex_triangles.resize(3 * mesh.triangles.size());
  fill.assign(mesh.vertex_triangle_offsets.begin(), mesh.vertex_triangle_offsets.end() - 1);
  mesh.vertex_corner_steps.resize(2 * mesh.vertex_triangles.size());
  for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    for (std::size_t corner = 0; corner < 3; ++corner) {
      const std::uint32_t k = fill[tri[corner]]++;
      mesh.vertex_triangles[k] = t;
      // A corner is u's first in the triangle (a degenerate triangle repeats a vertex; the sweep
      // has always stepped from the first). Edge j runs from corner j to j + 1: u -> next is edge
      // `at`, prev -> u is edge at + 2.
      const std::size_t at = tri[0] == tri[corner] ? 0 : (tri[1] == tri[corner] ? 1 : 2);
      const std::uint32_t next = tri[(at + 1) % 3];
      const std::uint32_t prev = tri[(at + 2) % 3];
      mesh.vertex_corner_steps[2 * std::size_t{k}] = {next, prev, mesh.edge_lengths[mesh.triangle_edges[t][at]]};
      mesh.vertex_corner_steps[2 * std::size_t{k} + 1] = {prev, next, mesh.edge_lengths[mesh.triangle_edges[t][(at + 2) % 3]]};
    }
  }
  mesh.boundary_vertex.assign(v_count, 0);
  for (std::size_t e = 0; e < mesh.edges.size(); ++e) {
    if (mesh.edge_triangles[e][1] < 0) mesh.boundary_vertex[mesh.edges[e][0]] = mesh.boundary_vertex[mesh.edges[e][1]] = 1;
  }
  return mesh;
}

namespace {

// The planar front through A (at ta) and B (at tb) reaching C, if its characteristic through C
// crosses the edge AB (upwind); +infinity otherwise. `length` is |B - A| (the corner-step table's
// length of that edge: the same number glm::length(b - a) gives, the difference's sign aside).
// The cheap rejections come first; every rejection gives +infinity whatever its order.
double triangleUpdate(const Vec3& a, const Vec3& b, const Vec3& c, double ta, double tb, double length) {
  const double d = tb - ta;
  if (!(length > 0.0) || std::abs(d) >= length) return kUnreached;
  const Vec3 ex = (b - a) / length;
  const Vec3 ac = c - a;
  const double xc = glm::dot(ac, ex);
  const double yc = glm::length(ac - xc * ex);
  if (!(yc > 0.0)) return kUnreached;
  const double gx = d / length;
  const double gy = std::sqrt(1.0 - gx * gx);
  const double foot = xc - yc / gy * gx;
  if (foot < 0.0 || foot > length) return kUnreached;
  const double t = ta + gx * xc + gy * yc;
  return t >= std::max(ta, tb) ? t : kUnreached;
}

// The mean edge length, or 1 without edges.
double meanEdge(const MeshTopology& mesh) {
  double sum = 0.0;
  for (const double l : mesh.edge_lengths) sum += l;
  return mesh.edge_lengths.empty() ? 1.0 : sum / static_cast<double>(mesh.edge_lengths.size());
}

// Vertices queued by value in buckets `width` wide, each bucket popped in any order (last in,
// first out). Each bucket is a stack threaded through one pool of entries, so that thousands of
// buckets cost no allocation of their own. A push below the bucket being popped lands in it.
class BucketQueue {
 public:
  BucketQueue(double width, std::size_t expected_pushes) : width_(width) {
    vertex_.reserve(expected_pushes);
    next_.reserve(expected_pushes);
  }

  void push(std::uint32_t v, double value) {
    const auto b = static_cast<std::size_t>(value / width_);
    if (b >= heads_.size()) heads_.resize(b + 1 + heads_.size() / 2, kEnd);
    std::uint32_t& head = heads_[std::max(b, current_)];
    vertex_.push_back(v);
    next_.push_back(head);
    head = static_cast<std::uint32_t>(vertex_.size() - 1);
  }

  // Takes the next vertex into `v`; false once the queue is empty.
  bool pop(std::uint32_t& v) {
    while (current_ < heads_.size() && heads_[current_] == kEnd) ++current_;
    if (current_ == heads_.size()) return false;
    const std::uint32_t top = heads_[current_];
    v = vertex_[top];
    heads_[current_] = next_[top];
    return true;
  }

 private:
  static constexpr std::uint32_t kEnd = std::numeric_limits<std::uint32_t>::max();
  double width_;
  std::size_t current_ = 0;
  std::vector<std::uint32_t> heads_;
  std::vector<std::uint32_t> vertex_;
  std::vector<std::uint32_t> next_;
};

}  // namespace

std::vector<double> surfaceDistance(const MeshTopology& mesh, std::span<const Vec3> positions,
                                    std::span<const std::uint32_t> sources, std::span<const double> initial) {
  const std::size_t v_count = mesh.vertex_offsets.size() - 1;
  std::vector<double> distance(v_count, kUnreached);
  std::vector<char> fixed(v_count, 0);
  // An untidy priority queue (Yatziv, Bartesaghi & Sapiro 2006): buckets kBucketEdges of a mean
  // edge wide, each popped in any order. Vertices within a bucket are fixed out of order by less
  // than its width, an error far below the level spacing (2 edges), for a queue without a heap.
  constexpr double kBucketEdges = 0.05;
  const double mean_edge = meanEdge(mesh);
  BucketQueue queue(mean_edge > 0.0 ? kBucketEdges * mean_edge : 1.0, 4 * v_count);
  for (std::size_t i = 0; i < sources.size(); ++i) {
    const std::uint32_t s = sources[i];
    assert(s < v_count);
    const double d0 = initial.empty() ? 0.0 : initial[i];
    if (d0 < distance[s]) distance[s] = d0;
  }
  for (const std::uint32_t s : sources) queue.push(s, distance[s]);
  auto offer = [&](std::uint32_t w, double candidate) {
    if (candidate < distance[w]) {
      distance[w] = candidate;
      queue.push(w, candidate);
    }
  };
  std::uint32_t u = 0;
  while (queue.pop(u)) {
    if (fixed[u]) continue;
    const double d = distance[u];
    fixed[u] = 1;
    // Each unfixed corner c of a triangle at u: the edge step from u, or the planar front through
    // u and the triangle's third corner o when o is fixed too; one offer per (triangle, corner).
    // The corner steps are the triangles' corners in the order the triangles list them at u; the
    // edge step takes the table's edge length (|c - u| and |u - c| are the same number).
    for (std::uint32_t k = 2 * mesh.vertex_triangle_offsets[u]; k < 2 * mesh.vertex_triangle_offsets[u + 1]; ++k) {
      const MeshTopology::CornerStep& step = mesh.vertex_corner_steps[k];
      const std::uint32_t c = step.corner;
      if (fixed[c]) continue;
      const std::uint32_t o = step.other;
      double candidate = d + step.length;
      // A planar update is never below max(d, distance[o]): where that cannot improve c, skip it
      // (offer takes only a candidate below distance[c]). Step k ^ 1 is the same triangle's other
      // corner: its length is |o - u|.
      if (fixed[o] && std::max(d, distance[o]) < distance[c]) {
        candidate = std::min(candidate, triangleUpdate(positions[u], positions[o], positions[c], d, distance[o],
                                                       mesh.vertex_corner_steps[k ^ 1U].length));
      }
      offer(c, candidate);
    }
    // Edges without a triangle at u (a wire edge of a non-manifold fan) still carry the front.
    if (mesh.vertex_triangle_offsets[u] == mesh.vertex_triangle_offsets[u + 1]) {
      for (std::uint32_t k = mesh.vertex_offsets[u]; k < mesh.vertex_offsets[u + 1]; ++k) {
        const std::uint32_t e = mesh.vertex_edges[k];
        const std::uint32_t w = mesh.edges[e][0] == u ? mesh.edges[e][1] : mesh.edges[e][0];
        if (!fixed[w]) offer(w, d + mesh.edge_lengths[e]);
      }
    }
  }
  return distance;
}

std::vector<double> edgeDistance(const MeshTopology& mesh, std::span<const std::uint32_t> sources) {
  const std::size_t v_count = mesh.vertex_offsets.size() - 1;
  std::vector<double> distance(v_count, kUnreached);
  // Label correcting over buckets a fifth of a mean edge wide (few vertices relaxed twice, few
  // empty buckets) instead of Dijkstra's heap: a vertex is relaxed again whenever its distance
  // drops after it was relaxed, so the result is the same fixed point d(w) = min over neighbours
  // u of d(u) + |uw| (floating-point addition is monotone, so that minimum is reached bit for bit
  // whatever the order).
  const double mean_edge = meanEdge(mesh);
  BucketQueue queue(mean_edge > 0.0 ? 0.2 * mean_edge : 1.0, 2 * v_count);
  std::vector<double> relaxed_at(v_count, kUnreached);  // the distance each vertex was last relaxed with
  for (const std::uint32_t s : sources) {
    assert(s < v_count);
    if (distance[s] > 0.0) {
      distance[s] = 0.0;
      queue.push(s, 0.0);
    }
  }
  std::uint32_t u = 0;
  while (queue.pop(u)) {
    const double d = distance[u];
    if (!(d < relaxed_at[u])) continue;
    relaxed_at[u] = d;
    for (std::uint32_t k = mesh.vertex_offsets[u]; k < mesh.vertex_offsets[u + 1]; ++k) {
      const std::uint32_t w = mesh.vertex_neighbours[k];
      const double candidate = d + mesh.vertex_edge_lengths[k];
      if (candidate < distance[w]) {
        distance[w] = candidate;
        queue.push(w, candidate);
      }
    }
  }
  return distance;
}

std::size_t sweepEdgeHops(const MeshTopology& mesh, std::uint32_t source, std::span<std::int32_t> hops,
                          std::span<std::uint32_t> queue) {
  assert(hops[source] < 0 && queue.size() > hops.size());
  // Whether a neighbour is new follows no pattern a branch predictor can learn, so each one is
  // written to the queue's next slot and kept only when it is new.
  queue[0] = source;
  hops[source] = 0;
  std::size_t tail = 1;
  for (std::size_t head = 0; head < tail; ++head) {
    const std::uint32_t u = queue[head];
    const std::int32_t next = hops[u] + 1;
    for (std::uint32_t k = mesh.vertex_offsets[u]; k < mesh.vertex_offsets[u + 1]; ++k) {
      const std::uint32_t w = mesh.vertex_neighbours[k];
      const std::int32_t h = hops[w];
      const std::int32_t fresh = h >> 31;  // all ones where h < 0 (not yet counted), else 0
      hops[w] = h ^ ((h ^ next) & fresh);
      queue[tail] = w;
      tail -= static_cast<std::size_t>(static_cast<std::ptrdiff_t>(fresh));
    }
  }
  return tail;
}

std::vector<std::int32_t> edgeHops(const MeshTopology& mesh, std::uint32_t source) {
  const std::size_t v_count = mesh.vertex_offsets.size() - 1;
  std::vector<std::int32_t> hops(v_count, -1);
  std::vector<std::uint32_t> queue(v_count + 1);
  sweepEdgeHops(mesh, source, hops, queue);
  return hops;
}

namespace {

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
