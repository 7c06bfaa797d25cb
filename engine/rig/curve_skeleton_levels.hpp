// SPDX-License-Identifier: MIT
// Iso-curves of a geodesic distance on a mesh and the graph they form (a discrete Reeb graph):
// what the rig needs from a mesh that has no skeleton yet. The distance f runs along the mesh's
// edges from a set of source vertices (Dijkstra); the levels f = k h cut the surface into slabs.
// Each connected piece of a slab is a region, each connected piece of a level is a contour (an
// iso-parametric curve of f: a ring around a limb), and a contour joins the region below it to
// the region above. On a genus-0 mesh the graph is a tree: a region with one contour is a tip,
// with two a piece of a tube, with three or more a junction where a limb leaves the body.
// Polygons are fanned into triangles; the cut points are exact on the edges (f is linear along
// an edge), so the rings are closed whatever the edge lengths, and every triangle's piece of a
// slab is connected to its neighbour's through their shared edge when that edge meets the slab.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "../core/iso_curve.hpp"
#include "../core/types.hpp"

namespace odeskin {

constexpr double kUnreached = std::numeric_limits<double>::infinity();

// Polygons fanned into triangles (orientation kept) with their edges: edge k of triangle t runs
// from corner k to corner k + 1. An edge with more than two triangles (non-manifold) links only
// its first two. Every vertex lists its edges (compressed rows) for the distance sweeps. Built in
// linear time (counting sorts), since it is part of the rig's measured time.
struct MeshTopology {
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::vector<std::array<std::uint32_t, 3>> triangle_edges;  // per triangle: index into edges
  std::vector<std::array<std::uint32_t, 2>> edges;           // vertex pairs, first < second
  std::vector<std::array<std::int32_t, 2>> edge_triangles;   // -1 where the edge has no second triangle
  std::vector<double> edge_lengths;                          // on the positions it was built with
  std::vector<std::uint32_t> vertex_offsets;                 // V + 1
  std::vector<std::uint32_t> vertex_edges;                   // the edges at each vertex
  std::vector<std::uint32_t> vertex_neighbours;              // beside vertex_edges: the edge's other end
  std::vector<double> vertex_edge_lengths;                   // beside vertex_edges: its length
  std::vector<std::uint32_t> vertex_triangle_offsets;        // V + 1
  std::vector<std::uint32_t> vertex_triangles;               // the triangles at each vertex
  // Beside vertex_triangles, two per triangle at vertex u: the corner c after u, then the one
  // before, each with the third corner o and |c - u| (the distance sweeps read them in order
  // instead of chasing triangles and edges across memory).
  struct CornerStep {
    std::uint32_t corner = 0;
    std::uint32_t other = 0;
    double length = 0.0;
  };
  std::vector<CornerStep> vertex_corner_steps;               // 2 x vertex_triangles.size()
  std::vector<char> boundary_vertex;                         // V: on an edge with one triangle
};
// `faces` must index below positions.size() (checked by the caller).
MeshTopology meshTopology(std::span<const Vec3> positions, const FaceList& faces);

// Distance over the surface from a set of source vertices (at their `initial` distances, 0 when
// empty): the fast marching method on triangles (Kimmel & Sethian 1998) with Dijkstra's edge step
// where a triangle gives no upwind update (obtuse corners, the first ring). Plain edge paths zig-zag
// on regular meshes (a ring grown on the cylinder's grid comes out V-shaped); the triangle update
// lets the front cross triangles straight. Vertices no edge path reaches keep kUnreached.
// Sources must be < the vertex count; initial, if given, one finite value >= 0 per source.
std::vector<double> surfaceDistance(const MeshTopology& mesh, std::span<const Vec3> positions,
                                    std::span<const std::uint32_t> sources, std::span<const double> initial = {});

// Dijkstra over the edges alone, every source at distance 0: cheaper than surfaceDistance and good
// enough where only the shape of the level tree matters (finding the body's centre).
std::vector<double> edgeDistance(const MeshTopology& mesh, std::span<const std::uint32_t> sources);

// Breadth-first edge counts from one vertex (-1: unreached): a cheap first sweep to an extremity.
std::vector<std::int32_t> edgeHops(const MeshTopology& mesh, std::uint32_t source);
// The sweep itself, into a caller's arrays: from `source` (hops[source] must be -1), every vertex
// reached through vertices whose hops are -1 gets its edge count from `source`. Returns how many
// it reached; queue[0, that count) holds them in the order of their counts (`queue` must hold
// hops.size() + 1 entries: the sweep writes one past the vertices it keeps). Vertices already
// counted stop the sweep, so one call per unreached vertex sweeps each connected component once.
std::size_t sweepEdgeHops(const MeshTopology& mesh, std::uint32_t source, std::span<std::int32_t> hops,
                          std::span<std::uint32_t> queue);

// One ring (or, where the mesh has a hole, an open arc) of f = level * spacing.
struct LevelContour {
  std::uint32_t level = 0;
  std::vector<CurvePoint> points;                     // one per crossed edge, a: the lower end
  std::vector<std::array<std::uint32_t, 2>> segments;  // one per crossed triangle: point indices
  bool closed = true;                                 // every point ends two segments
  std::uint32_t lower = 0;                            // the region below (slab level - 1)
  std::uint32_t upper = 0;                            // the region above (slab level)
  Vec3 centroid{0.0};                                 // length-weighted, on `positions`
  double length = 0.0;
  double radius = 0.0;                                // mean distance of the points from the centroid
};

// A connected piece of the slab spacing * slab <= f < spacing * (slab + 1).
struct LevelRegion {
  std::uint32_t slab = 0;
  std::vector<std::uint32_t> vertices;   // those with f in the slab (may be none for a thin piece)
  std::vector<std::uint32_t> contours;   // its boundary levels, both sides
  Vec3 centroid{0.0};                    // of its vertices (of its contours' centroids if none)
};

struct LevelGraph {
  double spacing = 0.0;
  std::vector<LevelRegion> regions;
  std::vector<LevelContour> contours;
  std::vector<std::uint32_t> vertex_region;  // V; kNoRegion for unreached vertices
  static constexpr std::uint32_t kNoRegion = std::numeric_limits<std::uint32_t>::max();
};

// f: V values >= 0 (kUnreached allowed: triangles touching such a vertex are left out);
// spacing > 0. Triangles with a corner out of range of f are a caller bug (asserted).
LevelGraph levelGraph(std::span<const Vec3> positions, const MeshTopology& mesh, std::span<const double> f,
                      double spacing);

// Position of a contour's length-weighted centroid on another pose of the same mesh.
Vec3 contourCentroid(const LevelContour& contour, std::span<const Vec3> positions);

}  // namespace odeskin
