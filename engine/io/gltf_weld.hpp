// SPDX-License-Identifier: MIT
// Seam welding (internal to odeskin_gltf). glTF splits a vertex wherever UVs or normals differ, so a
// seam appears as render vertices at one position. Analysis (adjacency, iso-curves, the ODE) needs
// the surface's topology, output needs the input's layout: weld, and keep the map back.
//
// Welding is by exact position equality (after decoding to double; -0 equals +0), not by a
// distance tolerance: exporters write each copy of a seam vertex from the same source vertex, so
// the copies are bit-identical, while a tolerance could merge distinct vertices that merely touch
// (closed lips, eyelids, fingers in contact) and tear the topology in the wrong place.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "../core/types.hpp"

namespace odeskin::gltf {

struct Welded {
  std::vector<Vec3> positions;                    // T topology vertices, in order of first appearance
  std::vector<std::uint32_t> topology_of_render;  // R: render vertex -> topology vertex
  std::vector<std::uint32_t> first_render;        // T: the first render vertex of each topology vertex
};

Welded weldEqualPositions(std::span<const Vec3> render_positions);

// Triangles (3 indices each) as a FaceList.
FaceList triangleFaces(std::span<const std::uint32_t> triangles);

// The render triangles over topology vertices. A triangle two of whose corners weld into one
// vertex has zero area; it is left out of the topology (it stays in the render faces).
FaceList topologyTriangles(std::span<const std::uint32_t> render_triangles,
                           std::span<const std::uint32_t> topology_of_render);

}  // namespace odeskin::gltf
