// SPDX-License-Identifier: MIT
#include "mesh_topology.hpp"

#include <algorithm>

#include <glm/geometric.hpp>

namespace odeskin {

MeshTopology meshTopology(std::span<const Vec3> positions, const FaceList& faces) {
  MeshTopology mesh;
  const std::size_t v_count = positions.size();
  for (std::size_t f = 0; f < faces.faceCount(); ++f) {
    const std::uint32_t begin = faces.face_offsets[f];
    const std::uint32_t end = faces.face_offsets[f + 1];
    for (std::uint32_t k = begin + 1; k + 1 < end; ++k) {
      mesh.triangles.push_back({faces.indices[begin], faces.indices[k], faces.indices[k + 1]});
    }
  }
  // Half-edges bucketed by their smaller vertex (a counting sort), then matched within a bucket.
  // Each is kept as one key, its larger vertex above its index 3 t + k: sorting a bucket's keys
  // orders its half-edges by their other end, then by index.
  const std::size_t h_count = 3 * mesh.triangles.size();
  std::vector<std::uint32_t> bucket(v_count + 1, 0);
  for (const auto& t : mesh.triangles) {
    for (std::uint32_t k = 0; k < 3; ++k) ++bucket[std::min(t[k], t[(k + 1) % 3]) + 1];
  }
  for (std::size_t v = 0; v < v_count; ++v) bucket[v + 1] += bucket[v];
  std::vector<std::uint64_t> half(h_count);
  {
    std::vector<std::uint32_t> fill(bucket.begin(), bucket.end() - 1);
    for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) {
      for (std::uint32_t k = 0; k < 3; ++k) {
        const std::uint32_t a = mesh.triangles[t][k];
        const std::uint32_t b = mesh.triangles[t][(k + 1) % 3];
        half[fill[std::min(a, b)]++] = static_cast<std::uint64_t>(std::max(a, b)) << 32 | (3 * t + k);
      }
    }
  }
  auto other = [](std::uint64_t key) { return static_cast<std::uint32_t>(key >> 32); };
  auto triangle = [](std::uint64_t key) { return static_cast<std::uint32_t>(key) / 3; };
  auto side = [](std::uint64_t key) { return static_cast<std::uint32_t>(key) % 3; };
  mesh.triangle_edges.resize(mesh.triangles.size());
  mesh.edges.reserve(h_count / 2);  // exact for a closed manifold mesh
  mesh.edge_triangles.reserve(h_count / 2);
  for (std::uint32_t v = 0; v < v_count; ++v) {
    std::sort(half.begin() + bucket[v], half.begin() + bucket[v + 1]);
    for (std::uint32_t i = bucket[v]; i < bucket[v + 1];) {
      const auto e = static_cast<std::uint32_t>(mesh.edges.size());
      const std::uint32_t w = other(half[i]);
      mesh.edges.push_back({v, w});
      mesh.edge_triangles.push_back({static_cast<std::int32_t>(triangle(half[i])), -1});
      std::uint32_t j = i;
      for (; j < bucket[v + 1] && other(half[j]) == w; ++j) {
        mesh.triangle_edges[triangle(half[j])][side(half[j])] = e;
        if (j == i + 1) mesh.edge_triangles.back()[1] = static_cast<std::int32_t>(triangle(half[j]));
      }
      i = j;
    }
  }
  mesh.edge_lengths.resize(mesh.edges.size());
  mesh.vertex_offsets.assign(v_count + 1, 0);
  for (std::size_t e = 0; e < mesh.edges.size(); ++e) {
    mesh.edge_lengths[e] = glm::length(positions[mesh.edges[e][1]] - positions[mesh.edges[e][0]]);
    ++mesh.vertex_offsets[mesh.edges[e][0] + 1];
    ++mesh.vertex_offsets[mesh.edges[e][1] + 1];
  }
  for (std::size_t v = 0; v < v_count; ++v) mesh.vertex_offsets[v + 1] += mesh.vertex_offsets[v];
  mesh.vertex_edges.resize(2 * mesh.edges.size());
  mesh.vertex_neighbours.resize(2 * mesh.edges.size());
  mesh.vertex_edge_lengths.resize(2 * mesh.edges.size());
  std::vector<std::uint32_t> fill(mesh.vertex_offsets.begin(), mesh.vertex_offsets.end() - 1);
  for (std::uint32_t e = 0; e < mesh.edges.size(); ++e) {
    for (int end = 0; end < 2; ++end) {
      const std::uint32_t k = fill[mesh.edges[e][static_cast<std::size_t>(end)]]++;
      mesh.vertex_edges[k] = e;
      mesh.vertex_neighbours[k] = mesh.edges[e][static_cast<std::size_t>(1 - end)];
      mesh.vertex_edge_lengths[k] = mesh.edge_lengths[e];
    }
  }
  mesh.vertex_triangle_offsets.assign(v_count + 1, 0);
  for (const auto& t : mesh.triangles) {
    for (const std::uint32_t v : t) ++mesh.vertex_triangle_offsets[v + 1];
  }
  for (std::size_t v = 0; v < v_count; ++v) mesh.vertex_triangle_offsets[v + 1] += mesh.vertex_triangle_offsets[v];
  mesh.vertex_triangles.resize(3 * mesh.triangles.size());
  fill.assign(mesh.vertex_triangle_offsets.begin(), mesh.vertex_triangle_offsets.end() - 1);
  mesh.vertex_corner_steps.resize(2 * mesh.vertex_triangles.size());
  for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    for (std::size_t corner = 0; corner < 3; ++corner) {
      const std::uint32_t k = fill[tri[corner]]++;
      mesh.vertex_triangles[k] = t;
      // A corner is u's first in the triangle (a degenerate triangle repeats a vertex; the sweep
      // has always stepped from the first). Edge j runs from corner j to j + 1: u -> next is edge
      // `at`, prev -> u is edge at + 2.
      const std::size_t at = tri[0] == tri[corner] ? 0 : (tri[1] == tri[corner] ? 1 : 2);
      const std::uint32_t next = tri[(at + 1) % 3];
      const std::uint32_t prev = tri[(at + 2) % 3];
      mesh.vertex_corner_steps[2 * std::size_t{k}] = {next, prev, mesh.edge_lengths[mesh.triangle_edges[t][at]]};
      mesh.vertex_corner_steps[2 * std::size_t{k} + 1] = {prev, next, mesh.edge_lengths[mesh.triangle_edges[t][(at + 2) % 3]]};
    }
  }
  mesh.boundary_vertex.assign(v_count, 0);
  for (std::size_t e = 0; e < mesh.edges.size(); ++e) {
    if (mesh.edge_triangles[e][1] < 0) mesh.boundary_vertex[mesh.edges[e][0]] = mesh.boundary_vertex[mesh.edges[e][1]] = 1;
  }
  return mesh;
}

}  // namespace odeskin
