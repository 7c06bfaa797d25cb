// SPDX-License-Identifier: MIT
// Axial and circumferential edge directions on a quad-dominant mesh: the ray-and-fan test (thesis
// 5.3; the spec has no text for it, so the design is from its name and purpose, docs/rigging.md).
//
// At a vertex p of a limb, a ray cast inward (against the vertex normal) meets the opposite wall
// at q: |pq| is the local diameter and the mid-point c an axis point (the ray). Every plane that
// contains the ray cuts the limb in a section through p and q; a fan of such planes, turned about
// the ray, holds the one across the limb, whose section is the shortest closed curve through p
// around c (a plane along the limb cuts it lengthwise, far longer or open). That plane's normal is
// the axial direction at p. The planes normal to p's own edge lines (projected on the tangent
// plane) are tried first, and the fan only where none of them closes round the axis point (or
// always, RayFanOptions::full_fan); each section walk stops as soon as it cannot be shorter than
// the shortest so far (see sectionLength), so a lengthwise one ends about a diameter out. Of p's edges, the ones most parallel to it are axial, the ones most
// perpendicular circumferential (at a valence-4 vertex the two of each, by rank). Axes are smoothed
// over each vertex's one-ring (principal direction of the neighbours' axes, which have no sign) and
// every edge takes the vote of its two ends, so a vertex whose ray left the mesh (a concave spot)
// or whose fan found no closed section (a junction) still gets a direction from its neighbours.
// Closed edge loops (edge_loops.hpp) whose edges are mostly circumferential are then the rings
// around the limbs, the iso-parametric curves; loops mostly axial run along the limbs.
// Since a loop's class is a majority anyway, RayFanOptions::loop_samples walks the loops first and
// runs the test only at a few vertices spread along each (the rig's mode: 1 vertex in 7 to 14 on
// the test tubes), and every edge takes its loop's class.
#pragma once

#include <cstdint>
#include <vector>

#include "../core/types.hpp"
#include "../mesh/poly_mesh.hpp"
#include "edge_loops.hpp"

namespace odeskin {

enum class EdgeDirection : std::uint8_t {
  kUnknown,          // neither end vertex has an axis
  kAxial,            // along the limb
  kCircumferential,  // around it
};

struct RayFanOptions {
  int fan_planes = 12;  // planes through the ray, 180 / 12 = 15 degrees apart (>= 2)
  // A section longer than this many ray lengths is not across the limb (a circle is pi long;
  // 3 pi admits cross-sections about 4:1 flat measured across their thin side).
  double max_section_diameters = 9.42477796076938;
  // false: the fan only where no plane across one of the vertex's own edge lines closes around
  // the axis point (on a quad limb one of them does, and it is all the edge classes need; 3x
  // faster); true: always the whole fan as well, for the axis between the edge lines.
  bool full_fan = false;
  // 0: the test at every vertex, axes smoothed over one-rings, each end votes on its edges. k > 0:
  // the maximal straight edge loops (edgeLoops) first, and the test only at vertices spread along
  // each loop until it has k decided votes (or no untested vertex left); a tested vertex votes for
  // every loop through it, each loop takes the majority of its votes and each edge its loop's class
  // (every edge is on one loop). Same classes on the test meshes with 1/7 to 1/14 of the rays.
  int loop_samples = 0;
};

// With loop_samples > 0 the per-vertex fields hold only the tested vertices (axes unsmoothed; 0,
// 0 and not measured elsewhere).
struct RayFanDirections {
  std::vector<Vec3> axes;            // V: unit axial direction after one-ring smoothing (0 where none)
  std::vector<double> diameters;     // V: ray length to the opposite wall (0: the ray found none)
  std::vector<char> measured;        // V: the fan found a closed section around the axis point
  std::vector<EdgeDirection> edges;  // per PolyMesh edge index
  std::vector<EdgeLoop> loops;       // loop_samples > 0: edgeLoops(mesh), which directedEdgeLoops reuses
  std::size_t tested_vertices = 0;   // vertices the ray and fan ran at (all of them with loop_samples 0)
  std::size_t measured_vertices = 0;
  std::size_t axial_edges = 0;
  std::size_t circumferential_edges = 0;
  std::size_t unknown_edges = 0;
};

// mesh: any polygon mesh (faces are fanned into triangles for the rays). options: fan_planes
// below 2 count as 2, a max_section_diameters that is not > 0 as the default. Runs the vertices
// in parallel (TBB); the result does not depend on the threads.
RayFanDirections rayFanDirections(const PolyMesh& mesh, const RayFanOptions& options = {});

// The loops of edgeLoops(mesh) that are closed, have >= min_points vertices and more than half of
// their edges circumferential (rings), and, in `axial`, those of >= min_points vertices with more
// than half axial (open or closed): the lines along the limbs. min_points >= 2.
struct DirectedLoops {
  std::vector<EdgeLoop> rings;
  std::vector<EdgeLoop> axial;
};
DirectedLoops directedEdgeLoops(const PolyMesh& mesh, const RayFanDirections& directions, std::size_t min_points);

}  // namespace odeskin
