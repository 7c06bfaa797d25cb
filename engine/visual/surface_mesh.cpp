// SPDX-License-Identifier: MIT
#include "surface_mesh.hpp"

#include <string>

#include <glm/geometric.hpp>

#include "../core/unit_vector.hpp"

namespace odeskin::visual {

Result<std::vector<std::uint32_t>> triangulateFaces(const FaceList& faces, std::size_t vertex_count) {
  const std::vector<std::uint32_t>& offsets = faces.face_offsets;
  if (offsets.empty() || offsets.front() != 0 || offsets.back() != faces.indices.size()) {
    return invalidArgument("faces: face_offsets must start at 0 and end at the index count");
  }
  std::vector<std::uint32_t> triangles;
  triangles.reserve(3 * faces.indices.size());
  for (std::size_t f = 0; f + 1 < offsets.size(); ++f) {
    const std::uint32_t begin = offsets[f];
    const std::uint32_t end = offsets[f + 1];
    if (end < begin || end - begin < 3) {
      return invalidArgument("faces: face " + std::to_string(f) + " has fewer than 3 corners");
    }
    for (std::uint32_t i = begin; i < end; ++i) {
      if (faces.indices[i] >= vertex_count) {
        return invalidArgument("faces: face " + std::to_string(f) + " uses vertex " + std::to_string(faces.indices[i]) +
                               " of " + std::to_string(vertex_count));
      }
    }
    for (std::uint32_t i = begin + 1; i + 1 < end; ++i) {
      triangles.push_back(faces.indices[begin]);
      triangles.push_back(faces.indices[i]);
      triangles.push_back(faces.indices[i + 1]);
    }
  }
  return triangles;
}

std::vector<Vec3> vertexNormals(std::span<const Vec3> positions, const FaceList& faces) {
  std::vector<Vec3> normals(positions.size(), Vec3(0.0));
  for (std::size_t f = 0; f < faces.faceCount(); ++f) {
    const std::uint32_t begin = faces.face_offsets[f];
    const std::uint32_t end = faces.face_offsets[f + 1];
    // Newell's method: exact for planar polygons, a sensible average for warped ones. Corners are
    // taken from the first one: products of absolute positions would cancel to noise on a face far
    // from the origin next to its size.
    const Vec3& origin = positions[faces.indices[begin]];
    Vec3 n(0.0);
    for (std::uint32_t i = begin; i < end; ++i) {
      const Vec3 p = positions[faces.indices[i]] - origin;
      const Vec3 q = positions[faces.indices[i + 1 < end ? i + 1 : begin]] - origin;
      n += glm::cross(p, q);
    }
    for (std::uint32_t i = begin; i < end; ++i) normals[faces.indices[i]] += n;
  }
  for (Vec3& n : normals) {
    // unitVector: on a tiny mesh (faces 1e-150 across) the area vector's squared length underflows.
    const Vec3 unit = unitVector(n);
    n = unit != Vec3(0.0) ? unit : Vec3(0.0, 0.0, 1.0);
  }
  return normals;
}

}  // namespace odeskin::visual
