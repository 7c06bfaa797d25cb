// SPDX-License-Identifier: MIT
// Iso-curves of a geodesic distance on a mesh and the graph they form (a discrete Reeb graph):
// what the rig needs from a mesh that has no skeleton yet. The distance f grows from a set of
// source vertices (surface_distance.hpp); the levels f = k h cut the surface into slabs.
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
#include "mesh_topology.hpp"
#include "surface_distance.hpp"

namespace odeskin {

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
