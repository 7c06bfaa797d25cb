// SPDX-License-Identifier: MIT
// Iso-curves of quad-dominant meshes from edge loops (thesis 5.3): from each edge, walk straight
// on through regular vertices (interior valence 4, or valence 3 along a boundary, all faces quads)
// with the half-edge step next -> opposite -> next. Loops that run across their part's axis are
// the part's rings; they become curves of vertex points, closed when the walk comes back.
#pragma once

#include <span>
#include <vector>

#include "../core/types.hpp"
#include "../mesh/poly_mesh.hpp"
#include "part_curves.hpp"
#include "part_segmentation.hpp"

namespace odeskin {

// Fraction of faces with exactly 4 corners (0 for no faces).
double quadFraction(const FaceList& faces);

// Every maximal straight edge walk, as vertex indices (a closed loop does not repeat its start).
// Every edge is on exactly one loop.
struct EdgeLoop {
  std::vector<std::uint32_t> vertices;
  bool closed = false;
  // PolyMesh edge indices, edges[j] from vertices[j] to vertices[j + 1] (closed: the last one
  // back to vertices[0]), filled by edgeLoops.
  std::vector<std::uint32_t> edges;
};
std::vector<EdgeLoop> edgeLoops(const PolyMesh& mesh);

// Rings (loops with >= min_points vertices, mostly across the axis of the part most of their
// vertices belong to), sorted along that axis into the part's sequence.
CurveLayout edgeLoopCurves(std::span<const Vec3> rest, const PolyMesh& mesh, const Segmentation& seg,
                           std::size_t min_points);

}  // namespace odeskin
