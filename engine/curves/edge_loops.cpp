// SPDX-License-Identifier: MIT
#include "edge_loops.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace odeskin {
namespace {

// A loop is a ring of its part when its edges are on average closer to perpendicular to the part
// axis than to parallel: mean |cos(edge, axis)| below cos 60 deg.
constexpr double kAcrossAxis = 0.5;

using Halfedge = PolyMesh::HalfedgeHandle;

// Interior valence 4 or boundary valence 3, and only quads around: "straight on" is defined.
// Once per vertex (a walk asks at every step, and each vertex is on two walks).
std::vector<char> regularVertices(const PolyMesh& mesh) {
  std::vector<char> quad(mesh.n_faces(), 0);
  for (auto f : mesh.faces()) quad[static_cast<std::size_t>(f.idx())] = mesh.valence(f) == 4 ? 1 : 0;
  std::vector<char> regular(mesh.n_vertices(), 0);
  for (auto v : mesh.vertices()) {
    const bool boundary = mesh.is_boundary(v);
    unsigned valence = 0;
    bool quads = true;
    for (auto h : mesh.voh_range(v)) {
      ++valence;
      const auto f = mesh.face_handle(h);
      quads = quads && (!f.is_valid() || quad[static_cast<std::size_t>(f.idx())]);
    }
    regular[static_cast<std::size_t>(v.idx())] = quads && valence == (boundary ? 3u : 4u) ? 1 : 0;
  }
  return regular;
}

// The half-edge that continues `h` straight on through its end vertex, or an invalid handle.
Halfedge straightOn(const PolyMesh& mesh, const std::vector<char>& regular, Halfedge h) {
  const PolyMesh::VertexHandle v = mesh.to_vertex_handle(h);
  if (!regular[static_cast<std::size_t>(v.idx())]) return Halfedge();
  if (mesh.is_boundary(v)) {
    // Along a boundary the walk follows the boundary; an interior edge ends there.
    if (mesh.is_boundary(h)) return mesh.next_halfedge_handle(h);
    const Halfedge opposite = mesh.opposite_halfedge_handle(h);
    if (mesh.is_boundary(opposite)) return mesh.opposite_halfedge_handle(mesh.prev_halfedge_handle(opposite));
    return Halfedge();
  }
  return mesh.next_halfedge_handle(mesh.opposite_halfedge_handle(mesh.next_halfedge_handle(h)));
}

}  // namespace

double quadFraction(const FaceList& faces) {
  const std::size_t count = faces.faceCount();
  if (count == 0) return 0.0;
  std::size_t quads = 0;
  for (std::size_t f = 0; f < count; ++f) quads += faces.face_offsets[f + 1] - faces.face_offsets[f] == 4 ? 1 : 0;
  return static_cast<double>(quads) / static_cast<double>(count);
}

std::vector<EdgeLoop> edgeLoops(const PolyMesh& mesh) {
  std::vector<EdgeLoop> loops;
  const std::vector<char> regular = regularVertices(mesh);
  std::vector<char> seen(mesh.n_edges(), 0);
  auto vertex = [&](Halfedge h) { return static_cast<std::uint32_t>(mesh.to_vertex_handle(h).idx()); };
  auto edge = [&](Halfedge h) { return static_cast<std::uint32_t>(mesh.edge_handle(h).idx()); };
  std::vector<std::uint32_t> back;
  std::vector<std::uint32_t> back_edges;
  // Plain handles throughout (a smart handle sliced to a plain one would drop its mesh pointer).
  for (std::size_t i = 0; i < mesh.n_edges(); ++i) {
    if (seen[i]) continue;
    seen[i] = 1;
    const OpenMesh::EdgeHandle e(static_cast<int>(i));
    const Halfedge h0 = mesh.halfedge_handle(e, 0);
    EdgeLoop loop;
    loop.vertices = {static_cast<std::uint32_t>(mesh.from_vertex_handle(h0).idx()), vertex(h0)};
    loop.edges = {static_cast<std::uint32_t>(e.idx())};
    for (Halfedge h = straightOn(mesh, regular, h0); h.is_valid(); h = straightOn(mesh, regular, h)) {
      if (h == h0) {
        loop.closed = true;
        loop.vertices.pop_back();  // the start vertex again
        break;
      }
      if (seen[edge(h)]) break;
      seen[edge(h)] = 1;
      loop.vertices.push_back(vertex(h));
      loop.edges.push_back(edge(h));
    }
    if (!loop.closed) {
      back.clear();
      back_edges.clear();
      for (Halfedge h = straightOn(mesh, regular, mesh.opposite_halfedge_handle(h0)); h.is_valid(); h = straightOn(mesh, regular, h)) {
        if (seen[edge(h)]) break;
        seen[edge(h)] = 1;
        back.push_back(vertex(h));
        back_edges.push_back(edge(h));
      }
      loop.vertices.insert(loop.vertices.begin(), back.rbegin(), back.rend());
      loop.edges.insert(loop.edges.begin(), back_edges.rbegin(), back_edges.rend());
    }
    loops.push_back(std::move(loop));
  }
  return loops;
}

CurveLayout edgeLoopCurves(std::span<const Vec3> rest, const PolyMesh& mesh, const Segmentation& seg,
                           std::size_t min_points) {
  CurveLayout layout;
  layout.sequences.resize(seg.parts.size());
  for (EdgeLoop& loop : edgeLoops(mesh)) {
    if (loop.vertices.size() < min_points) continue;
    std::vector<std::size_t> votes(seg.parts.size(), 0);
    for (std::uint32_t v : loop.vertices) ++votes[seg.vertex_part[v]];
    const auto p = static_cast<std::uint32_t>(std::max_element(votes.begin(), votes.end()) - votes.begin());
    const Vec3 axis = seg.parts[p].axis;
    double across = 0.0;
    std::size_t segments = 0;
    const std::size_t n = loop.vertices.size();
    for (std::size_t j = 0; j + (loop.closed ? 0 : 1) < n; ++j) {
      const Vec3 e = rest[loop.vertices[(j + 1) % n]] - rest[loop.vertices[j]];
      const double len = glm::length(e);
      if (!(len > 0.0)) continue;
      across += std::abs(glm::dot(e, axis)) / len;
      ++segments;
    }
    if (segments == 0 || across / static_cast<double>(segments) >= kAcrossAxis) continue;
    CurveDraft draft;
    for (std::uint32_t v : loop.vertices) draft.points.push_back({v, v, 0.0});
    draft.closed = loop.closed;
    draft.bone = seg.parts[p].bone;
    measureCurve(draft, rest);
    std::vector<Vec3> points;
    for (std::uint32_t v : loop.vertices) points.push_back(rest[v]);
    const PrincipalAxes pca = principalAxes(points);
    Vec3 normal = loop.closed && pca.values[0] <= 0.25 * pca.values[1] ? pca.axes[0] : axis;
    if (glm::dot(normal, axis) < 0.0) normal = -normal;
    layout.sequences[p].push_back({static_cast<std::uint32_t>(layout.curves.size()), {draft.centroid, normal}});
    layout.curves.push_back(std::move(draft));
  }
  for (std::size_t p = 0; p < seg.parts.size(); ++p) {
    const Vec3 axis = seg.parts[p].axis;
    std::stable_sort(layout.sequences[p].begin(), layout.sequences[p].end(), [&](const Station& a, const Station& b) {
      return glm::dot(a.plane.origin, axis) < glm::dot(b.plane.origin, axis);
    });
  }
  return layout;
}

}  // namespace odeskin
