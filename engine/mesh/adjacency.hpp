// SPDX-License-Identifier: MIT
// Vertex one-ring neighbours as compressed rows (sorted, unique), from polygon faces.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "../core/types.hpp"

namespace odeskin {

struct VertexAdjacency {
  std::vector<std::uint32_t> offsets{0};  // V + 1
  std::vector<std::uint32_t> neighbours;

  std::span<const std::uint32_t> of(std::uint32_t vertex) const {
    return {neighbours.data() + offsets[vertex], neighbours.data() + offsets[vertex + 1]};
  }
};

// Vertices joined by a face edge; face indices must be < vertex_count (checked by the readers).
VertexAdjacency vertexAdjacency(const FaceList& faces, std::size_t vertex_count);

// Mean length of the mesh's edges (each counted once) at `positions`; 0 without edges. The curve
// spacing of iso-curve identification is a multiple of it.
double meanEdgeLength(std::span<const Vec3> positions, const VertexAdjacency& adjacency);

}  // namespace odeskin
