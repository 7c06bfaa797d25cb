// SPDX-License-Identifier: MIT
// Where the curve rig's second distance pass starts (curve_skeleton.cpp): a band across the body
// at its centre, so that the rings run across the body on both sides of it. Found from the shape
// alone: the body's centroid, a point deep inside the body near it, and the body's shortest
// section through that point (least_girth.hpp). Nothing here depends on the vertex numbering, so
// neither does the skeleton.
#pragma once

#include <cstdint>
#include <optional>
#include <span>

#include "../core/types.hpp"
#include "least_girth.hpp"
#include "mesh_topology.hpp"

namespace odeskin {

// `component`: the vertices of one connected surface; `in_component`: per vertex of the mesh,
// whether it is one of them. Triangles are the component's where their first corner is.

// The centroid of the volume the component encloses where it is closed but for small holes (at
// most 1% of its vertices on a rim): the torso holds most of the volume, where the surface's
// centroid is pulled out along thin limbs and ears. Else, or where it encloses next to nothing,
// the centroid of its surface. Moments are taken about the box centre, so that the result moves
// with the mesh.
Vec3 bodyCentroid(std::span<const Vec3> rest, const MeshTopology& mesh, std::span<const std::uint32_t> component,
                  std::span<const char> in_component);

// A point deep inside the body: the middle of the longest stretch inside it along 13 lines through
// `centroid` (the vertices' principal axes, and the diagonals between them). The centroid itself
// may lie in a thin part, or outside the body (a curled pose); the longest stretch runs through
// the torso. Crossings alternate out, in, out along a line through a closed surface, so the
// stretches need no orientation; a line with an odd count (through a hole) is left out. Empty
// where no line has a stretch.
std::optional<Vec3> longestChordMiddle(std::span<const Vec3> rest, const MeshTopology& mesh,
                                       std::span<const std::uint32_t> component, std::span<const char> in_component,
                                       const Vec3& centroid);

// The band: the shortest section of the component through the longest chord's middle (the
// centroid where there is none). The search starts from the principal axes of the vertices near
// that point, within three times the distance to the nearest vertex (which holds an oval section
// about it), and doubles that reach while no plane gives a loop around the point. Empty where
// none does at any reach (a surface with no inside, such as a mask, whose sections are arcs).
std::optional<GirthPlane> bodySection(std::span<const Vec3> rest, const MeshTopology& mesh,
                                      std::span<const std::uint32_t> component, std::span<const char> in_component);

}  // namespace odeskin
