// SPDX-License-Identifier: MIT
#include "hard_edges.hpp"

#include <limits>
#include <string>

#include "../core/finite_vector.hpp"
#include "../core/smoothing_groups.hpp"

namespace odeskin {
namespace {

Status checkNormals(std::span<const Vec3> normals, std::size_t count, bool render_layout) {
  if (normals.size() != count) {
    return invalidArgument("runtime asset: render normals: " + std::to_string(normals.size()) + " normals for " +
                           std::to_string(count) + (render_layout ? " render vertices" : " vertices"));
  }
  for (std::size_t r = 0; r < normals.size(); ++r) {
    const Vec3& n = normals[r];
    if (!isFinite(n)) {
      return invalidArgument("runtime asset: render normals: normal " + std::to_string(r) + " is not finite");
    }
    if (n == Vec3(0.0)) {
      return invalidArgument("runtime asset: render normals: normal " + std::to_string(r) +
                             " is zero; glTF normals are unit vectors");
    }
  }
  return okStatus();
}

}  // namespace

Result<std::optional<RenderCorners>> buildRenderCorners(std::span<const std::uint32_t> topology, std::size_t vertex_count,
                                                        std::span<const std::uint32_t> render_triangles,
                                                        std::span<const std::uint32_t> corner_offsets,
                                                        std::span<const gpu::Corner> corners,
                                                        std::span<const Vec3> normals) {
  ODESKIN_TRY(checkNormals(normals, topology.empty() ? vertex_count : topology.size(), !topology.empty()));
  if (topology.empty()) return std::optional<RenderCorners>();  // one copy per vertex: no hard edge

  const SmoothingGroups groups = smoothingGroups(topology, vertex_count, normals);
  if (groups.hard_vertices == 0) return std::optional<RenderCorners>();
  const std::size_t render_count = topology.size();
  RenderCorners out;
  out.hard_vertices = groups.hard_vertices;

  // A hard vertex's group sums the corners of the render triangles at its own copies, in triangle
  // order; every other render vertex takes its topology vertex's corners as they are.
  std::vector<std::vector<gpu::Corner>> group_corners(groups.group_count);
  for (std::size_t t = 0; t + 2 < render_triangles.size(); t += 3) {
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = render_triangles[t + k];
      if (!groups.hard[topology[a]]) continue;
      const std::uint32_t b = render_triangles[t + (k + 1) % 3], c = render_triangles[t + (k + 2) % 3];
      group_corners[groups.group_of_render[a]].push_back(gpu::Corner{topology[b], topology[c]});
    }
  }
  out.offsets.reserve(render_count + 1);
  out.offsets.push_back(0);
  for (std::size_t r = 0; r < render_count; ++r) {
    const std::uint32_t i = topology[r];
    if (groups.hard[i]) {
      const std::vector<gpu::Corner>& own = group_corners[groups.group_of_render[r]];
      out.corners.insert(out.corners.end(), own.begin(), own.end());
    } else {
      out.corners.insert(out.corners.end(), corners.begin() + corner_offsets[i], corners.begin() + corner_offsets[i + 1]);
    }
    if (out.corners.size() > std::numeric_limits<std::uint32_t>::max()) {
      return outOfRange("runtime asset: render normals: more than 2^32 render corners");
    }
    out.offsets.push_back(static_cast<std::uint32_t>(out.corners.size()));
  }
  return std::optional<RenderCorners>(std::move(out));
}

}  // namespace odeskin
