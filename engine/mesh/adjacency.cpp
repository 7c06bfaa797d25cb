// SPDX-License-Identifier: MIT
#include "adjacency.hpp"

#include <algorithm>

namespace odeskin {

VertexAdjacency vertexAdjacency(const FaceList& faces, std::size_t vertex_count) {
  std::vector<std::vector<std::uint32_t>> rows(vertex_count);
  for (std::size_t f = 0; f < faces.faceCount(); ++f) {
    const std::uint32_t begin = faces.face_offsets[f];
    const std::uint32_t n = faces.face_offsets[f + 1] - begin;
    for (std::uint32_t k = 0; k < n; ++k) {
      const std::uint32_t a = faces.indices[begin + k];
      const std::uint32_t b = faces.indices[begin + (k + 1) % n];
      rows[a].push_back(b);
      rows[b].push_back(a);
    }
  }
  VertexAdjacency adjacency;
  adjacency.offsets.reserve(vertex_count + 1);
  for (auto& row : rows) {
    std::sort(row.begin(), row.end());
    row.erase(std::unique(row.begin(), row.end()), row.end());
    adjacency.neighbours.insert(adjacency.neighbours.end(), row.begin(), row.end());
    adjacency.offsets.push_back(static_cast<std::uint32_t>(adjacency.neighbours.size()));
  }
  return adjacency;
}

}  // namespace odeskin
