// SPDX-License-Identifier: MIT
#include "surface_distance.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

namespace odeskin {
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
      const bool fresh = h < 0;
      const std::int32_t mask = -static_cast<std::int32_t>(fresh);  // all ones where w is new
      hops[w] = h ^ ((h ^ next) & mask);
      queue[tail] = w;
      tail += static_cast<std::size_t>(fresh);
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

}  // namespace odeskin
