// SPDX-License-Identifier: MIT
#include "hard_edges.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include <limits>
#include <string>

#include <glm/geometric.hpp>

namespace odeskin {
namespace {

constexpr std::uint32_t kNoGroup = std::numeric_limits<std::uint32_t>::max();

Status checkNormals(std::span<const gpu::Float4> normals, std::size_t count, bool render_layout) {
  if (normals.size() != count) {
    return invalidArgument("runtime asset: render normals: " + std::to_string(normals.size()) + " normals for " +
                           std::to_string(count) + (render_layout ? " render vertices" : " vertices"));
  }
  for (std::size_t r = 0; r < normals.size(); ++r) {
    const gpu::Float4& n = normals[r];
    if (!std::isfinite(n.x) || !std::isfinite(n.y) || !std::isfinite(n.z)) {
      return invalidArgument("runtime asset: render normals: normal " + std::to_string(r) + " is not finite");
    }
    if (n.x == 0.0f && n.y == 0.0f && n.z == 0.0f) {
      return invalidArgument("runtime asset: render normals: normal " + std::to_string(r) +
                             " is zero; glTF normals are unit vectors");
    }
  }
  return okStatus();
}

Vec3 unit(const gpu::Float4& n) {
  const Vec3 v(n.x, n.y, n.z);
  const double scale = std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)});
  return glm::normalize(v / scale);  // scaled first: a normal given as 1e-30 long does not underflow
}

}  // namespace

Result<std::optional<RenderCorners>> buildRenderCorners(std::span<const std::uint32_t> topology, std::size_t vertex_count,
                                                        std::span<const std::uint32_t> render_triangles,
                                                        std::span<const std::uint32_t> corner_offsets,
                                                        std::span<const gpu::Corner> corners,
                                                        std::span<const gpu::Float4> normals) {
  ODESKIN_TRY(checkNormals(normals, topology.empty() ? vertex_count : topology.size(), !topology.empty()));
  if (topology.empty()) return std::optional<RenderCorners>();  // one copy per vertex: no hard edge

  // Each topology vertex's copies, in render order, then their smoothing groups: a copy joins the
  // first group whose first normal is within kSmoothingGroupAngle of its own.
  const std::size_t render_count = topology.size();
  std::vector<std::uint32_t> copy_offsets(vertex_count + 1, 0);
  for (const std::uint32_t i : topology) ++copy_offsets[i + 1];
  for (std::size_t i = 0; i < vertex_count; ++i) copy_offsets[i + 1] += copy_offsets[i];
  std::vector<std::uint32_t> copies(render_count);
  std::vector<std::uint32_t> fill(copy_offsets.begin(), copy_offsets.end() - 1);
  for (std::size_t r = 0; r < render_count; ++r) copies[fill[topology[r]]++] = static_cast<std::uint32_t>(r);

  const double same = std::cos(kSmoothingGroupAngle);
  std::vector<std::uint32_t> group_of(render_count, kNoGroup);
  std::vector<bool> hard(vertex_count, false);
  std::vector<std::pair<std::uint32_t, Vec3>> firsts;  // this vertex's groups: number, first copy's normal
  std::uint32_t groups = 0;
  RenderCorners out;
  for (std::size_t i = 0; i < vertex_count; ++i) {
    firsts.clear();
    for (std::uint32_t c = copy_offsets[i]; c < copy_offsets[i + 1]; ++c) {
      const std::uint32_t r = copies[c];
      const Vec3 n = unit(normals[r]);
      // Only a group's first copy stands for it, so membership cannot drift along a fan of copies.
      for (const auto& [group, first] : firsts) {
        if (glm::dot(first, n) >= same) {
          group_of[r] = group;
          break;
        }
      }
      if (group_of[r] == kNoGroup) {
        group_of[r] = groups++;
        firsts.emplace_back(group_of[r], n);
      }
    }
    if (firsts.size() > 1) {
      hard[i] = true;
      ++out.hard_vertices;
    }
  }
  if (out.hard_vertices == 0) return std::optional<RenderCorners>();

  // A hard vertex's group sums the corners of the render triangles at its own copies, in triangle
  // order; every other render vertex takes its topology vertex's corners as they are.
  std::vector<std::vector<gpu::Corner>> group_corners(groups);
  for (std::size_t t = 0; t + 2 < render_triangles.size(); t += 3) {
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = render_triangles[t + k];
      if (!hard[topology[a]]) continue;
      const std::uint32_t b = render_triangles[t + (k + 1) % 3], c = render_triangles[t + (k + 2) % 3];
      group_corners[group_of[a]].push_back(gpu::Corner{topology[b], topology[c]});
    }
  }
  out.offsets.reserve(render_count + 1);
  out.offsets.push_back(0);
  for (std::size_t r = 0; r < render_count; ++r) {
    const std::uint32_t i = topology[r];
    if (hard[i]) {
      const std::vector<gpu::Corner>& own = group_corners[group_of[r]];
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
