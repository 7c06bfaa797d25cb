// SPDX-License-Identifier: MIT
// The shortest cross-section of a body through a point inside it. The curve rig's second distance
// pass starts from a band across the body at its centre (curve_skeleton.cpp), and that band has to
// lie square across the body whatever the vertex order. Rings of a distance grown from one tip
// cross a torso at a slant that depends on which tip it was; the plane that cuts the torso in the
// shortest loop around the point depends only on the shape.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "../core/types.hpp"
#include "mesh_topology.hpp"

namespace odeskin {

struct GirthPlane {
  Vec3 normal{0.0};
  double girth = 0.0;                   // the length of the loop
  std::vector<std::uint32_t> vertices;  // the ends of the edges the loop crosses, ascending
  std::vector<double> distances;        // beside vertices: their distances to the plane
};

// Two unit vectors square to the unit vector `n` and to each other: axes in the plane with normal
// `n`, or across the line along it.
std::array<Vec3, 2> squareTo(const Vec3& n);

// Of the planes through `centre`, the one whose section of the mesh has the shortest closed loop
// around `centre` (an odd number of loops around it: the centre inside the section): the
// best of `starts` (normals, need not be unit), refined by a pattern search about it to under a
// degree. Only triangles within `reach` of the centre count, and only those of vertices
// `include` marks (all if empty); a loop leaving them does not (a closed loop around the centre
// that leaves the ball is at least 2 * reach long). Pieces hanging off the surface (a hole's
// rim, a fin on an edge) are left out of the loops, and the triangles' orientation does not
// matter. Empty when no start gives such a loop (the centre outside the body, or a surface with
// no inside). Nothing in it depends on the vertex numbering.
std::optional<GirthPlane> leastGirthPlane(std::span<const Vec3> positions, const MeshTopology& mesh, const Vec3& centre,
                                          double reach, std::span<const Vec3> starts, std::span<const char> include = {});

}  // namespace odeskin
