// SPDX-License-Identifier: MIT
// Smoothing groups of a render layout from its bind normals. glTF splits a vertex for two reasons:
// a UV seam, where the copies share a normal, and a hard edge, where each copy has the normal of
// its own faces. Only the normals tell the two apart: the copies of a topology vertex whose normals
// point the same way form one group, and a vertex with more than one group is on a hard edge.
// The runtime (engine/runtime/hard_edges.hpp) and the glTF export (engine/export/export_mesh.hpp)
// then give each group the normal of its own faces.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "finite_vector.hpp"
#include "types.hpp"

namespace odeskin {

// Two bind normals are one group when they are within this angle (radians): wide enough for a
// normal stored as normalized bytes (KHR_mesh_quantization, about 0.5 degree apart), far below any
// crease an artist marks.
inline constexpr double kSmoothingGroupAngle = 0.02;  // about 1.1 degrees

struct SmoothingGroups {
  std::vector<std::uint32_t> group_of_render;  // R: group number, < group_count
  std::vector<bool> hard;                      // V: the topology vertex has more than one group
  std::uint32_t group_count = 0;
  std::uint32_t hard_vertices = 0;
};

// Whether a bind normal can stand for a direction: finite and not zero (any length).
inline bool isUsableNormal(const Vec3& n) {
  return isFinite(n) && n != Vec3(0.0);
}

// `topology`: render vertex -> topology vertex (each < vertex_count); `normals`: one per render
// vertex, each isUsableNormal (callers check). A copy joins the first group of its
// vertex, in render order, whose first copy's normal is within kSmoothingGroupAngle of its own.
SmoothingGroups smoothingGroups(std::span<const std::uint32_t> topology, std::size_t vertex_count,
                                std::span<const Vec3> normals);

}  // namespace odeskin
