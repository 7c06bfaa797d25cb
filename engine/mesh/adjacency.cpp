// SPDX-License-Identifier: MIT
#include "adjacency.hpp"

#include <algorithm>
#include <cstddef>
#include <limits>

#include <glm/geometric.hpp>

namespace odeskin {

VertexAdjacency vertexAdjacency(const FaceList& faces, std::size_t vertex_count) {
  // Compressed rows in two passes (count, fill), then each row sorted and deduplicated in place:
  // no per-vertex allocation.
  std::vector<std::uint32_t> start(vertex_count + 1, 0);
  auto edges = [&](auto&& visit) {
    for (std::size_t f = 0; f < faces.faceCount(); ++f) {
      const std::uint32_t begin = faces.face_offsets[f];
      const std::uint32_t n = faces.face_offsets[f + 1] - begin;
      for (std::uint32_t k = 0; k < n; ++k) visit(faces.indices[begin + k], faces.indices[begin + (k + 1) % n]);
    }
  };
  edges([&](std::uint32_t a, std::uint32_t b) {
    ++start[a + 1];
    ++start[b + 1];
  });
  for (std::size_t v = 0; v < vertex_count; ++v) start[v + 1] += start[v];
  std::vector<std::uint32_t> all(start.back());
  std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
  edges([&](std::uint32_t a, std::uint32_t b) {
    all[fill[a]++] = b;
    all[fill[b]++] = a;
  });
  VertexAdjacency adjacency;
  adjacency.offsets.resize(vertex_count + 1);
  adjacency.offsets[0] = 0;
  // Each row drops its repeats first (most edges come once from each of their two faces), then
  // sorts what is left: half as many entries to sort.
  std::vector<std::uint32_t> last_row(vertex_count, std::numeric_limits<std::uint32_t>::max());
  std::size_t out = 0;
  for (std::size_t v = 0; v < vertex_count; ++v) {
    const std::size_t row_begin = out;
    for (std::uint32_t k = start[v]; k < start[v + 1]; ++k) {
      const std::uint32_t w = all[k];
      if (last_row[w] == v) continue;
      last_row[w] = static_cast<std::uint32_t>(v);
      all[out++] = w;
    }
    std::sort(all.begin() + static_cast<std::ptrdiff_t>(row_begin), all.begin() + static_cast<std::ptrdiff_t>(out));
    adjacency.offsets[v + 1] = static_cast<std::uint32_t>(out);
  }
  all.resize(out);
  adjacency.neighbours = std::move(all);
  return adjacency;
}

double meanEdgeLength(std::span<const Vec3> positions, const VertexAdjacency& adjacency) {
  double sum = 0.0;
  std::size_t edges = 0;
  for (std::uint32_t i = 0; i < positions.size(); ++i) {
    for (std::uint32_t j : adjacency.of(i)) {
      if (j <= i) continue;
      sum += glm::length(positions[j] - positions[i]);
      ++edges;
    }
  }
  return edges > 0 ? sum / static_cast<double>(edges) : 0.0;
}

}  // namespace odeskin
