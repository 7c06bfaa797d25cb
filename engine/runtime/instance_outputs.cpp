// SPDX-License-Identifier: MIT
#include "instance_outputs.hpp"

#include <algorithm>

#include <glm/geometric.hpp>

namespace odeskin {
namespace {

glm::vec3 xyz(const gpu::Float4& f) { return {f.x, f.y, f.z}; }

}  // namespace

void computeVertexNormals(std::span<const std::uint32_t> corner_offsets, std::span<const gpu::Corner> corners,
                          std::span<const gpu::Float4> positions, std::span<gpu::Float4> normals) {
  const std::size_t count = std::min(positions.size(), normals.size());
  for (std::size_t i = 0; i < count && i + 1 < corner_offsets.size(); ++i) {
    const glm::vec3 p = xyz(positions[i]);
    glm::vec3 n(0.0f);
    for (std::uint32_t k = corner_offsets[i]; k < corner_offsets[i + 1]; ++k) {
      const gpu::Corner c = corners[k];
      n += glm::cross(xyz(positions[c.next]) - p, xyz(positions[c.prev]) - p);
    }
    const float length = glm::length(n);
    n = length > 0.0f ? n / length : glm::vec3(0.0f);
    normals[i] = gpu::Float4{n.x, n.y, n.z, 0.0f};
  }
}

InstanceBounds computeBounds(std::span<const gpu::Float4> positions) {
  InstanceBounds b;
  for (const gpu::Float4& p : positions) {
    b.min = glm::min(b.min, xyz(p));
    b.max = glm::max(b.max, xyz(p));
  }
  return b;
}

InstanceBounds decodeBounds(const gpu::BoundsKeys& keys) {
  InstanceBounds b;
  // The reset value 0xFFFFFFFF sorts above every float's key, so it survives only without vertices.
  if (keys.keys[0] == 0xFFFFFFFFu) return b;
  for (int c = 0; c < 3; ++c) {
    b.min[c] = gpu::fromOrderedKey(keys.keys[c]);
    b.max[c] = -gpu::fromOrderedKey(keys.keys[4 + c]);
  }
  return b;
}

}  // namespace odeskin
