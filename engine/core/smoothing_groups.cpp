// SPDX-License-Identifier: MIT
#include "smoothing_groups.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include <glm/geometric.hpp>

#include "unit_vector.hpp"

namespace odeskin {

SmoothingGroups smoothingGroups(std::span<const std::uint32_t> topology, std::size_t vertex_count,
                                std::span<const Vec3> normals) {
  // Each topology vertex's copies, in render order.
  std::vector<std::uint32_t> copy_offsets(vertex_count + 1, 0);
  for (const std::uint32_t i : topology) ++copy_offsets[i + 1];
  for (std::size_t i = 0; i < vertex_count; ++i) copy_offsets[i + 1] += copy_offsets[i];
  std::vector<std::uint32_t> copies(topology.size());
  std::vector<std::uint32_t> fill(copy_offsets.begin(), copy_offsets.end() - 1);
  for (std::size_t r = 0; r < topology.size(); ++r) copies[fill[topology[r]]++] = static_cast<std::uint32_t>(r);

  const double same = std::cos(kSmoothingGroupAngle);
  SmoothingGroups out;
  out.group_of_render.assign(topology.size(), 0);
  out.hard.assign(vertex_count, false);
  std::vector<std::pair<std::uint32_t, Vec3>> firsts;  // this vertex's groups: number, first copy's normal
  for (std::size_t i = 0; i < vertex_count; ++i) {
    firsts.clear();
    for (std::uint32_t c = copy_offsets[i]; c < copy_offsets[i + 1]; ++c) {
      const std::uint32_t r = copies[c];
      const Vec3 n = unitVector(normals[r]);
      // Only a group's first copy stands for it, so membership cannot drift along a fan of copies.
      const auto joined = std::find_if(firsts.begin(), firsts.end(),
                                       [&](const auto& group) { return glm::dot(group.second, n) >= same; });
      if (joined != firsts.end()) {
        out.group_of_render[r] = joined->first;
      } else {
        out.group_of_render[r] = out.group_count;
        firsts.emplace_back(out.group_count++, n);
      }
    }
    if (firsts.size() > 1) {
      out.hard[i] = true;
      ++out.hard_vertices;
    }
  }
  return out;
}

}  // namespace odeskin
