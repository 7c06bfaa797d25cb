// SPDX-License-Identifier: MIT
// Intersecting a plane with a patch of the mesh (thesis 6.3.1): polygons are fanned into
// triangles, the crossing edges are chained face to face, and each crossing point becomes a
// CurvePoint (a, b, t) on its edge, snapped to the edge's end when t or 1 - t is within the
// threshold of thesis Fig. 6.4 (relative to the edge length).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "../core/iso_curve.hpp"
#include "../core/types.hpp"
#include "part_curves.hpp"

namespace odeskin {

struct CutMesh {
  std::vector<std::array<std::uint32_t, 3>> triangles;  // polygon fans, orientation kept
  std::vector<std::array<std::int32_t, 3>> neighbours;  // across edge k = (t[k], t[k+1]); -1 on the boundary
  std::vector<std::uint32_t> vertex_offsets;            // V + 1
  std::vector<std::uint32_t> vertex_triangles;          // triangles around each vertex
};

// `faces` must be valid, manifold and consistently oriented (buildPolyMesh accepted them).
CutMesh buildCutMesh(const FaceList& faces, std::size_t vertex_count);

// A patch of the cut mesh that many planes are cut with (a body part and its margin): its
// triangles, and once it has been cut a few times a bounding-box tree over them, so that finding
// the triangles a plane crosses costs about their number and the tree's depth, not the patch's
// size (a part is cut ~ extent / spacing times, which grows as the mesh is refined; parts cut a
// few times, the usual case at ~10^4 vertices, are scanned and never pay for a tree: the tree
// comes after kScansBeforeTree scans, a count measured on the cat).
class CutRegion {
 public:
  static constexpr std::size_t kScansBeforeTree = 32;

  CutRegion() = default;
  // `triangles`: indices into mesh.triangles (any order, no repeats); `mesh` and `positions` must
  // outlive the region. The tree is built on the query after `scans_before_tree` scans (the same
  // cuts either way: tests set 0, a tree at once, or SIZE_MAX, never).
  CutRegion(const CutMesh& mesh, std::span<const Vec3> positions, std::vector<std::uint32_t> triangles,
            std::size_t scans_before_tree = kScansBeforeTree);

  std::span<const std::uint32_t> triangles() const { return triangles_; }  // ascending
  bool contains(std::uint32_t triangle) const;
  // Whether the region has its tree yet.
  bool indexed() const { return !nodes_.empty(); }
  // Appends to `out` the region's triangles whose bounding boxes the plane may meet: every triangle
  // with corners on both sides of it, and some others near it (in tree order; all of them,
  // ascending, while the region has no tree). Not thread safe (it may build the tree).
  void nearPlane(const Plane& plane, std::vector<std::uint32_t>& out) const;

 private:
  void buildTree() const;
  struct Node {
    Vec3 lo{0.0}, hi{0.0};
    std::uint32_t first = 0, count = 0;  // a leaf's range of order_ (count > 0)
    std::uint32_t right = 0;             // an inner node's second child (the first follows it)
  };
  std::uint32_t build(std::span<const Vec3> lo, std::span<const Vec3> hi, std::span<const Vec3> centre,
                      std::uint32_t first, std::uint32_t last) const;

  const CutMesh* mesh_ = nullptr;
  std::span<const Vec3> positions_;
  std::vector<std::uint32_t> triangles_;  // ascending
  std::size_t scans_before_tree_ = kScansBeforeTree;
  // The tree, built on demand (a cache: the region's contents never change).
  mutable std::size_t scans_ = 0;
  mutable std::vector<std::uint32_t> order_;  // the triangles in tree order
  mutable std::vector<Node> nodes_;
};

struct PlaneCut {
  std::vector<CurvePoint> points;  // snapped, no two consecutive equal (nor last == first when closed)
  bool closed = false;
  Vec3 centroid{0.0};  // length-weighted
  double length = 0.0;  // including the closing segment of a closed chain
  double radius = 0.0;  // mean distance of the points from the centroid
  std::size_t owned = 0;  // points on an edge touching an owned vertex
};

// Reusable scratch for many cuts of one mesh (not thread safe).
class PlaneCutter {
 public:
  PlaneCutter(const CutMesh& mesh, std::span<const Vec3> positions, double snap_threshold);

  // The triangles with at least one corner in `vertices`, ascending.
  std::vector<std::uint32_t> trianglesTouching(std::span<const std::uint32_t> vertices);

  // The best chain of plane ∩ `triangles` (a vertex exactly on the plane counts as in front, so
  // every crossed triangle has exactly two crossing edges and chains never branch): the one with
  // the most points on edges touching an `owned` vertex (all vertices when `owned` is empty), then
  // the longest. A chain closes when it comes back to its first triangle; it stays open where it
  // leaves `triangles` or the mesh. nullopt when the plane crosses none of the triangles.
  std::optional<PlaneCut> bestChain(std::span<const std::uint32_t> triangles, const Plane& plane,
                                    const std::function<bool(std::uint32_t)>& owned = {});
  // The same on a prepared region (the same chain as bestChain(region.triangles(), ...)).
  std::optional<PlaneCut> bestChain(const CutRegion& region, const Plane& plane,
                                    const std::function<bool(std::uint32_t)>& owned = {});

 private:
  struct DirectedEdge {
    std::uint32_t u, v;
  };
  bool crossing(std::uint32_t triangle, const Plane& plane, int& entry, int& exit) const;
  PlaneCut makeCut(const std::vector<DirectedEdge>& edges, bool closed, const Plane& plane,
                   const std::function<bool(std::uint32_t)>& owned) const;
  void nextEpoch();

  const CutMesh& mesh_;
  std::span<const Vec3> positions_;
  double snap_;
  std::vector<std::uint32_t> member_;
  std::vector<std::uint32_t> visited_;
  std::vector<std::uint32_t> candidates_;
  std::uint32_t epoch_ = 0;
};

}  // namespace odeskin
