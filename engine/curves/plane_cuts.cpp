// SPDX-License-Identifier: MIT
#include "plane_cuts.hpp"

#include <algorithm>
#include <limits>
#include <numeric>

#include <glm/geometric.hpp>

#include "median_split.hpp"

namespace odeskin {
namespace {

bool samePoint(const CurvePoint& p, const CurvePoint& q) {
  return (p.a == q.a && p.b == q.b && p.t == q.t) || (p.a == q.b && p.b == q.a && p.t == 1.0 - q.t);
}

}  // namespace

CutMesh buildCutMesh(const FaceList& faces, std::size_t vertex_count) {
  CutMesh mesh;
  mesh.triangles.reserve(faces.indices.size() > 2 * faces.faceCount() ? faces.indices.size() - 2 * faces.faceCount() : 0);
  for (std::size_t f = 0; f < faces.faceCount(); ++f) {
    const std::uint32_t begin = faces.face_offsets[f];
    const std::uint32_t n = faces.face_offsets[f + 1] - begin;
    for (std::uint32_t k = 1; k + 1 < n; ++k) {
      mesh.triangles.push_back({faces.indices[begin], faces.indices[begin + k], faces.indices[begin + k + 1]});
    }
  }
  const std::size_t count = mesh.triangles.size();
  mesh.vertex_offsets.assign(vertex_count + 1, 0);
  for (const auto& tri : mesh.triangles) {
    for (std::uint32_t v : tri) ++mesh.vertex_offsets[v + 1];
  }
  for (std::size_t v = 0; v < vertex_count; ++v) mesh.vertex_offsets[v + 1] += mesh.vertex_offsets[v];
  mesh.vertex_triangles.resize(mesh.vertex_offsets.back());
  // Around each v, the j-th triangle: its corner after v (next), before v (prev), and which of
  // its edges runs prev -> v (edge k runs from corner k to corner k + 1).
  const std::size_t corners = mesh.vertex_triangles.size();
  std::vector<std::uint32_t> next(corners), prev(corners);
  std::vector<std::uint8_t> edge_into(corners);
  std::vector<std::uint32_t> fill(mesh.vertex_offsets.begin(), mesh.vertex_offsets.end() - 1);
  for (std::uint32_t t = 0; t < count; ++t) {
    for (std::uint32_t k = 0; k < 3; ++k) {
      const std::uint32_t v = mesh.triangles[t][k];
      const std::uint32_t j = fill[v]++;
      next[j] = mesh.triangles[t][k == 2 ? 0 : k + 1];
      prev[j] = mesh.triangles[t][k == 0 ? 2 : k - 1];
      edge_into[j] = static_cast<std::uint8_t>(k == 0 ? 2 : k - 1);
      mesh.vertex_triangles[j] = t;
    }
  }
  // Consistent orientation: the neighbour across (u, v) is the triangle around v that runs v -> u
  // (the last one, should a broken mesh have several). Each triangle's edge into v is matched
  // against v's own list, so both scans stay in one short stretch of memory.
  mesh.neighbours.assign(count, {-1, -1, -1});
  for (std::size_t v = 0; v < vertex_count; ++v) {
    const std::uint32_t begin = mesh.vertex_offsets[v];
    const std::uint32_t end = mesh.vertex_offsets[v + 1];
    for (std::uint32_t i = begin; i < end; ++i) {
      const std::uint32_t u = prev[i];
      std::int32_t across = -1;
      for (std::uint32_t j = begin; j < end; ++j) {
        if (next[j] == u) across = static_cast<std::int32_t>(mesh.vertex_triangles[j]);
      }
      mesh.neighbours[mesh.vertex_triangles[i]][edge_into[i]] = across;
    }
  }
  return mesh;
}

namespace {

// Triangles per leaf of a region's tree.
constexpr std::uint32_t kLeafTriangles = 8;
// A box is skipped only when it clears the plane by more than the rounding of the signed distances
// measured against it, relative to the distances involved: the exact crossing test decides the rest.
constexpr double kPlaneSlack = 1e-9;

}  // namespace

CutRegion::CutRegion(const CutMesh& mesh, std::span<const Vec3> positions, std::vector<std::uint32_t> triangles,
                     std::size_t scans_before_tree)
    : mesh_(&mesh), positions_(positions), triangles_(std::move(triangles)), scans_before_tree_(scans_before_tree) {
  if (!std::is_sorted(triangles_.begin(), triangles_.end())) std::sort(triangles_.begin(), triangles_.end());
  if (scans_before_tree_ == 0) buildTree();
}

void CutRegion::buildTree() const {
  const std::size_t count = triangles_.size();
  if (count == 0 || !nodes_.empty()) return;
  std::vector<Vec3> lo(count), hi(count), centre(count);
  for (std::size_t k = 0; k < count; ++k) {
    const auto& tri = mesh_->triangles[triangles_[k]];
    lo[k] = glm::min(glm::min(positions_[tri[0]], positions_[tri[1]]), positions_[tri[2]]);
    hi[k] = glm::max(glm::max(positions_[tri[0]], positions_[tri[1]]), positions_[tri[2]]);
    centre[k] = 0.5 * (lo[k] + hi[k]);
  }
  order_.resize(count);
  std::iota(order_.begin(), order_.end(), 0u);  // local indices while building
  nodes_.reserve(2 * (count / kLeafTriangles + 1));
  build(lo, hi, centre, 0, static_cast<std::uint32_t>(count));
  for (std::uint32_t& k : order_) k = triangles_[k];
}

std::uint32_t CutRegion::build(std::span<const Vec3> lo, std::span<const Vec3> hi, std::span<const Vec3> centre,
                               std::uint32_t first, std::uint32_t last) const {
  const auto index = static_cast<std::uint32_t>(nodes_.size());
  nodes_.emplace_back();
  if (last - first <= kLeafTriangles) {
    Vec3 box_lo(std::numeric_limits<double>::infinity()), box_hi(-std::numeric_limits<double>::infinity());
    for (std::uint32_t k = first; k < last; ++k) {
      box_lo = glm::min(box_lo, lo[order_[k]]);
      box_hi = glm::max(box_hi, hi[order_[k]]);
    }
    nodes_[index].lo = box_lo;
    nodes_[index].hi = box_hi;
    nodes_[index].first = first;
    nodes_[index].count = last - first;
    return index;
  }
  // Median split along the widest spread of the triangles' centres; boxes from the children up.
  const std::uint32_t middle = splitAtMedian(order_, centre, first, last);
  const std::uint32_t left = build(lo, hi, centre, first, middle);
  const std::uint32_t right = build(lo, hi, centre, middle, last);
  nodes_[index].lo = glm::min(nodes_[left].lo, nodes_[right].lo);
  nodes_[index].hi = glm::max(nodes_[left].hi, nodes_[right].hi);
  nodes_[index].right = right;
  return index;
}

bool CutRegion::contains(std::uint32_t triangle) const {
  return std::binary_search(triangles_.begin(), triangles_.end(), triangle);
}

void CutRegion::nearPlane(const Plane& plane, std::vector<std::uint32_t>& out) const {
  if (nodes_.empty() && scans_ < scans_before_tree_) {
    ++scans_;
    out.insert(out.end(), triangles_.begin(), triangles_.end());
    return;
  }
  buildTree();
  if (nodes_.empty()) return;  // no triangles
  const Vec3 n_abs = glm::abs(plane.normal);
  std::uint32_t stack[64];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    const Vec3 centre = 0.5 * (node.lo + node.hi);
    const double reach = glm::dot(n_abs, 0.5 * (node.hi - node.lo));
    const double distance = glm::dot(plane.normal, centre - plane.origin);
    const double slack = kPlaneSlack * (reach + glm::length(centre - plane.origin)) +
                         kPlaneSlack * glm::length(plane.origin);
    if (distance - reach > slack || distance + reach < -slack) continue;
    if (node.count > 0) {
      out.insert(out.end(), order_.begin() + node.first, order_.begin() + node.first + node.count);
    } else {
      const auto self = static_cast<std::uint32_t>(&node - nodes_.data());
      stack[top++] = node.right;
      stack[top++] = self + 1;
    }
  }
}

PlaneCutter::PlaneCutter(const CutMesh& mesh, std::span<const Vec3> positions, double snap_threshold)
    : mesh_(mesh), positions_(positions), snap_(snap_threshold), member_(mesh.triangles.size(), 0),
      visited_(mesh.triangles.size(), 0) {}

void PlaneCutter::nextEpoch() {
  // cppcheck-suppress knownConditionTrueFalse ; false positive: the unsigned epoch wraps to 0 after 2^32 cuts
  if (++epoch_ == 0) {
    std::fill(member_.begin(), member_.end(), 0u);
    std::fill(visited_.begin(), visited_.end(), 0u);
    epoch_ = 1;
  }
}

std::vector<std::uint32_t> PlaneCutter::trianglesTouching(std::span<const std::uint32_t> vertices) {
  nextEpoch();
  std::vector<std::uint32_t> out;
  for (std::uint32_t v : vertices) {
    for (std::uint32_t k = mesh_.vertex_offsets[v]; k < mesh_.vertex_offsets[v + 1]; ++k) {
      const std::uint32_t t = mesh_.vertex_triangles[k];
      if (member_[t] == epoch_) continue;
      member_[t] = epoch_;
      out.push_back(t);
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

bool PlaneCutter::crossing(std::uint32_t triangle, const Plane& plane, int& entry, int& exit) const {
  bool front[3];
  for (int k = 0; k < 3; ++k) {
    front[k] = glm::dot(plane.normal, positions_[mesh_.triangles[triangle][static_cast<std::size_t>(k)]] - plane.origin) >= 0.0;
  }
  if (front[0] == front[1] && front[1] == front[2]) return false;
  for (int k = 0; k < 3; ++k) {
    if (front[k] && !front[(k + 1) % 3]) exit = k;
    if (!front[k] && front[(k + 1) % 3]) entry = k;
  }
  return true;
}

PlaneCut PlaneCutter::makeCut(const std::vector<DirectedEdge>& edges, bool closed, const Plane& plane,
                              const std::function<bool(std::uint32_t)>& owned) const {
  PlaneCut cut;
  cut.closed = closed;
  for (const DirectedEdge& e : edges) {
    const double du = glm::dot(plane.normal, positions_[e.u] - plane.origin);
    const double dv = glm::dot(plane.normal, positions_[e.v] - plane.origin);
    const double t = std::clamp(du / (du - dv), 0.0, 1.0);  // du and dv differ in sign, so du != dv
    CurvePoint p{e.u, e.v, t};
    if (t <= snap_) p = {e.u, e.u, 0.0};
    else if (t >= 1.0 - snap_) p = {e.v, e.v, 0.0};
    if (cut.points.empty() || !samePoint(cut.points.back(), p)) cut.points.push_back(p);
    cut.owned += !owned || owned(e.u) || owned(e.v) ? 1 : 0;
  }
  while (closed && cut.points.size() > 1 && samePoint(cut.points.back(), cut.points.front())) cut.points.pop_back();
  const std::size_t n = cut.points.size();
  std::vector<Vec3> pos(n);
  for (std::size_t j = 0; j < n; ++j) pos[j] = curvePointPosition(positions_, cut.points[j]);
  Vec3 weighted(0.0);
  Vec3 mean(0.0);
  for (std::size_t j = 0; j < n; ++j) {
    mean += pos[j];
    if (j + 1 == n && !closed) break;
    const Vec3& next = pos[(j + 1) % n];
    const double len = glm::length(next - pos[j]);
    cut.length += len;
    weighted += len * 0.5 * (pos[j] + next);
  }
  cut.centroid = cut.length > 0.0 ? weighted / cut.length : mean / static_cast<double>(std::max<std::size_t>(n, 1));
  for (const Vec3& p : pos) cut.radius += glm::length(p - cut.centroid);
  if (n > 0) cut.radius /= static_cast<double>(n);
  return cut;
}

std::optional<PlaneCut> PlaneCutter::bestChain(std::span<const std::uint32_t> triangles, const Plane& plane,
                                               const std::function<bool(std::uint32_t)>& owned) {
  return bestChain(CutRegion(mesh_, positions_, {triangles.begin(), triangles.end()}), plane, owned);
}

std::optional<PlaneCut> PlaneCutter::bestChain(const CutRegion& region, const Plane& plane,
                                               const std::function<bool(std::uint32_t)>& owned) {
  nextEpoch();
  // Chains start from the crossed triangles in ascending order, as a scan of the whole region
  // would meet them (the first of equally good chains wins).
  candidates_.clear();
  region.nearPlane(plane, candidates_);
  if (region.indexed()) std::sort(candidates_.begin(), candidates_.end());
  auto inside = [&](std::int32_t t) { return t >= 0 && region.contains(static_cast<std::uint32_t>(t)); };
  auto edgeOf = [&](std::uint32_t t, int k) {
    return DirectedEdge{mesh_.triangles[t][static_cast<std::size_t>(k)], mesh_.triangles[t][static_cast<std::size_t>((k + 1) % 3)]};
  };
  std::optional<PlaneCut> best;
  std::vector<DirectedEdge> forward, backward;
  for (std::uint32_t t0 : candidates_) {
    int entry0 = 0, exit0 = 0;
    if (visited_[t0] == epoch_ || !crossing(t0, plane, entry0, exit0)) continue;
    visited_[t0] = epoch_;
    forward.assign({edgeOf(t0, entry0), edgeOf(t0, exit0)});
    bool closed = false;
    // Forward: leave each triangle through its exit edge; the neighbour enters through it.
    for (std::uint32_t t = t0, exit = static_cast<std::uint32_t>(exit0);;) {
      const std::int32_t nb = mesh_.neighbours[t][exit];
      if (!inside(nb)) break;
      const auto next = static_cast<std::uint32_t>(nb);
      if (next == t0) {
        closed = true;
        forward.pop_back();  // t0's entry edge again
        break;
      }
      int entry = 0, out = 0;
      if (visited_[next] == epoch_ || !crossing(next, plane, entry, out)) break;
      visited_[next] = epoch_;
      forward.push_back(edgeOf(next, out));
      t = next;
      exit = static_cast<std::uint32_t>(out);
    }
    backward.clear();
    for (std::uint32_t t = t0, entry = static_cast<std::uint32_t>(entry0); !closed;) {
      const std::int32_t nb = mesh_.neighbours[t][entry];
      if (!inside(nb)) break;
      const auto prev = static_cast<std::uint32_t>(nb);
      int in = 0, out = 0;
      if (visited_[prev] == epoch_ || !crossing(prev, plane, in, out)) break;
      visited_[prev] = epoch_;
      backward.push_back(edgeOf(prev, in));
      t = prev;
      entry = static_cast<std::uint32_t>(in);
    }
    if (!backward.empty()) {
      std::reverse(backward.begin(), backward.end());
      backward.insert(backward.end(), forward.begin(), forward.end());
      forward.swap(backward);
    }
    PlaneCut cut = makeCut(forward, closed, plane, owned);
    if (!best || cut.owned > best->owned || (cut.owned == best->owned && cut.length > best->length)) best = std::move(cut);
  }
  return best;
}

}  // namespace odeskin
