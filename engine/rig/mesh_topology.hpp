// SPDX-License-Identifier: MIT
// The connectivity the curve rig's distance sweeps and level graphs walk (surface_distance.hpp,
// curve_skeleton_levels.hpp), built once per mesh.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "../core/types.hpp"

namespace odeskin {

// Polygons fanned into triangles (orientation kept) with their edges: edge k of triangle t runs
// from corner k to corner k + 1. An edge with more than two triangles (non-manifold) links only
// its first two. Every vertex lists its edges (compressed rows) for the distance sweeps. Built in
// linear time (counting sorts), since it is part of the rig's measured time.
struct MeshTopology {
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::vector<std::array<std::uint32_t, 3>> triangle_edges;  // per triangle: index into edges
  std::vector<std::array<std::uint32_t, 2>> edges;           // vertex pairs, first < second
  std::vector<std::array<std::int32_t, 2>> edge_triangles;   // -1 where the edge has no second triangle
  std::vector<double> edge_lengths;                          // on the positions it was built with
  std::vector<std::uint32_t> vertex_offsets;                 // V + 1
  std::vector<std::uint32_t> vertex_edges;                   // the edges at each vertex
  std::vector<std::uint32_t> vertex_neighbours;              // beside vertex_edges: the edge's other end
  std::vector<double> vertex_edge_lengths;                   // beside vertex_edges: its length
  std::vector<std::uint32_t> vertex_triangle_offsets;        // V + 1
  std::vector<std::uint32_t> vertex_triangles;               // the triangles at each vertex
  // Beside vertex_triangles, two per triangle at vertex u: the corner c after u, then the one
  // before, each with the third corner o and |c - u| (the distance sweeps read them in order
  // instead of chasing triangles and edges across memory).
  struct CornerStep {
    std::uint32_t corner = 0;
    std::uint32_t other = 0;
    double length = 0.0;
  };
  std::vector<CornerStep> vertex_corner_steps;               // 2 x vertex_triangles.size()
  std::vector<char> boundary_vertex;                         // V: on an edge with one triangle
};
// `faces` must index below positions.size() (checked by the caller).
MeshTopology meshTopology(std::span<const Vec3> positions, const FaceList& faces);

}  // namespace odeskin
