// SPDX-License-Identifier: MIT
// The per-instance outputs besides positions: vertex normals recomputed from the deformed
// triangles (with the corner lists they gather from; per render vertex across hard edges), the
// axis-aligned bounding box, and the outputs gathered into a glTF asset's render vertices. CPU references of
// shaders/instance_normals.comp, of the bounds reduction in shaders/instanced_deform.comp and of
// shaders/render_gather.comp (same float operations, same order).
#pragma once

#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "../core/types.hpp"
#include "runtime_layout.hpp"

namespace odeskin {

// Fans of every polygon, and around each vertex the (next, prev) of its triangles in face order:
// the gather list instance_normals.comp and computeVertexNormals walk in the same order.
//   triangles: appended, 3 indices each; offsets: V + 1; corners: 3 per triangle.
void buildCorners(const FaceList& faces, std::size_t vertex_count, std::vector<std::uint32_t>& triangles,
                  std::vector<std::uint32_t>& offsets, std::vector<gpu::Corner>& corners);
// The fans of every polygon of `faces`, appended to `triangles` (3 indices each), in the order
// buildCorners makes them.
void appendFanTriangles(const FaceList& faces, std::vector<std::uint32_t>& triangles);

// Render vertex r of one instance is topology vertex topology_of_render[r] (RenderLayout): glTF
// input split at UV and normal seams gets its deformed positions and normals back in its own
// vertices, so an engine binds them beside its UVs. Entries [begin, end) of `out` only.
//   topology: V entries; topology_of_render, out: R each.
void gatherRenderVertices(std::span<const std::uint32_t> topology_of_render, std::span<const gpu::Float4> topology,
                          std::span<gpu::Float4> out, std::size_t begin, std::size_t end);

// Why recomputed, not rotated: the analytic residual (series and remainders) changes the surface's
// shape between keys, which the bones' rotation of rest normals cannot show. Each normal is the
// area-weighted sum of its triangles' normals, sum cross(p[next] - p[i], p[prev] - p[i]) over the
// vertex's corners, normalised; (0, 0, 0) where that sum is zero (no triangle, or degenerate ones).
// A gather per vertex rather than a scatter per face: no float atomics, so the order of the sum is
// fixed and the GPU and CPU results differ only by rounding.
//   corner_offsets: V + 1, corners: corner_offsets[V] (RuntimeAsset::cornerOffsets / corners);
//   positions, normals: V each (xyz; normals get w = 0).
void computeVertexNormals(std::span<const std::uint32_t> corner_offsets, std::span<const gpu::Corner> corners,
                          std::span<const gpu::Float4> positions, std::span<gpu::Float4> normals);
// The normals of vertices [begin, end) only (positions and normals still the whole instance's), so
// threads can share one instance; each vertex's normal is the same number either way.
void computeVertexNormals(std::span<const std::uint32_t> corner_offsets, std::span<const gpu::Corner> corners,
                          std::span<const gpu::Float4> positions, std::span<gpu::Float4> normals,
                          std::size_t begin, std::size_t end);

// Normals of render vertices [begin, end) of one instance on an asset with hard edges, from
// their own corner lists (RuntimeAsset::renderCornerOffsets / renderCorners): computeVertexNormals'
// sum, with render vertex r's own position positions[topology[r]]. A render vertex off the hard
// edges has its topology vertex's corners, so its normal equals the gathered one to the bit.
//   corner_offsets: R + 1; topology, normals: R; positions: V (the instance's topology vertices).
void computeRenderNormals(std::span<const std::uint32_t> corner_offsets, std::span<const gpu::Corner> corners,
                          std::span<const std::uint32_t> topology, std::span<const gpu::Float4> positions,
                          std::span<gpu::Float4> normals, std::size_t begin, std::size_t end);

// Axis-aligned box of one instance's deformed vertices; empty (min = +inf, max = -inf) without any.
struct InstanceBounds {
  glm::vec3 min{std::numeric_limits<float>::infinity()};
  glm::vec3 max{-std::numeric_limits<float>::infinity()};
  bool empty() const { return !(min.x <= max.x); }
  // Grows this box by `later`, the box of vertices after this one's: the same box as one pass over
  // both, to the bit (ties keep the earlier value, as the pass does).
  void merge(const InstanceBounds& later);
};

// Min and max of the xyz of `positions` (exact: no rounding is involved).
InstanceBounds computeBounds(std::span<const gpu::Float4> positions);
// Decodes the GPU's ordered keys (runtime_layout.h); untouched keys (no vertex) give an empty box.
InstanceBounds decodeBounds(const gpu::BoundsKeys& keys);

}  // namespace odeskin
