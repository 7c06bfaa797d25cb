// SPDX-License-Identifier: MIT
// What a renderer needs from a polygon mesh: triangles (each polygon as a fan) and smooth vertex
// normals (area-weighted, so small slivers do not tilt the shading).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "../core/result.hpp"
#include "../core/types.hpp"

namespace odeskin::visual {

// Face f = (v0, v1, ..., vk) becomes (v0, v1, v2), (v0, v2, v3), ..., (v0, v(k-1), vk): exact for
// the convex polygons of OBJ and glTF meshes. Three indices per triangle. kInvalidArgument naming
// the face: fewer than 3 corners, an index >= vertex_count, or malformed offsets.
Result<std::vector<std::uint32_t>> triangulateFaces(const FaceList& faces, std::size_t vertex_count);

// Unit vertex normals: the sum of the Newell normals (twice the vector area) of the faces around
// each vertex, normalised. A vertex in no face, or whose faces cancel out, gets +z. Precondition:
// `faces` index into `positions` (triangulateFaces checks this).
std::vector<Vec3> vertexNormals(std::span<const Vec3> positions, const FaceList& faces);

}  // namespace odeskin::visual
