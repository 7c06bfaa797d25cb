// SPDX-License-Identifier: MIT
// A mesh with one outer rim laid over the unit square: the parameter domain of a curve network
// extracted from a mesh (thesis sec. 4.7; mesh_network.hpp).
//  - Inner boundary loops (a face's mouth or eyes) are closed by a fan of triangles around one added
//    vertex, the mean of the loop's vertices, so the mesh becomes a topological disk. A hole centre
//    is the same combination of its loop in every pose, so samples that fall in a hole move with it.
//  - The rim (the longest loop) goes onto the square's boundary. Four rim vertices become the
//    corners: the extremes along the diagonals of the mesh's two widest principal directions. The
//    rim arcs between them become the sides, by chord length.
//  - Every other vertex is placed by Floater's mean-value coordinates (Floater 2003): the weighted
//    mean of its neighbours with weights (tan(a/2) + tan(b/2)) / |x_j - x_i|, a and b the angles at
//    x_i beside edge ij. The weights are positive for any triangle, so by the Tutte-Floater theorem
//    the map onto the convex square is one to one, whatever the mesh's shape.
// u runs along the second principal direction (a face's height), v along the first (its width);
// v's sign is chosen so that (S_u x S_v) points the way the mesh's faces do.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "../core/result.hpp"
#include "../core/types.hpp"

namespace odeskin {

using Vec2 = glm::dvec2;

struct MeshDisk {
  std::size_t vertex_count = 0;                       // the mesh's own vertices
  std::vector<std::uint32_t> rim;                     // the outer loop, in order, starting at corners[0]
  std::vector<std::vector<std::uint32_t>> holes;      // inner loops; hole h's centre is disk vertex vertex_count + h
  std::vector<std::array<std::uint32_t, 3>> triangles;  // the mesh's faces (polygons as fans), then the hole fans
  std::array<std::uint32_t, 4> corners{};             // rim vertices at (u, v) = (0, 0), (0, 1), (1, 1), (1, 0)
  std::vector<Vec2> uv;                               // per disk vertex (mesh's, then hole centres), in [0, 1]^2

  std::size_t diskVertexCount() const { return vertex_count + holes.size(); }
};

// The mesh's positions followed by the hole centres (each the mean of its loop's positions).
// Precondition: positions.size() == disk.vertex_count.
std::vector<Vec3> diskPositions(const MeshDisk& disk, std::span<const Vec3> positions);

// The disk and its parameters. kInvalidArgument (the message names the vertex, edge or face) for:
// fewer than 3 vertices; positions not finite or too large or small for double-precision lengths
// (checkedPositionBox, vertices numbered from 1); a face index out of range; a vertex in no face;
// an edge used by more than two faces or twice in one direction (not manifold, or faces not
// consistently oriented); a vertex
// where two boundary loops touch; a closed mesh (no rim); a mesh that is not a disk once its holes
// are filled (several pieces, or handles: V - E + F != 1); a rim of fewer than 4 vertices or whose
// four corners do not follow each other around it; a zero-length edge or a face with a straight
// angle (a mean-value weight would be infinite). kIllPosed if the linear solve fails.
Result<MeshDisk> parameteriseDisk(std::span<const Vec3> positions, const FaceList& faces);

}  // namespace odeskin
