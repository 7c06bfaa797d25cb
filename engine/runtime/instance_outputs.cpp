// SPDX-License-Identifier: MIT
#include "instance_outputs.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace odeskin {
namespace {

glm::vec3 xyz(const gpu::Float4& f) { return {f.x, f.y, f.z}; }

#if defined(__SSE2__)

// One corner's cross(a, b) on xyz lanes: (a.y b.z - b.y a.z, a.z b.x - b.z a.x, a.x b.y - b.x a.y),
// glm::cross's products and differences, each rounded as it rounds them.
inline __m128 cross(__m128 a, __m128 b) {
  const __m128 a_yzx = _mm_shuffle_ps(a, a, _MM_SHUFFLE(3, 0, 2, 1));
  const __m128 a_zxy = _mm_shuffle_ps(a, a, _MM_SHUFFLE(3, 1, 0, 2));
  const __m128 b_yzx = _mm_shuffle_ps(b, b, _MM_SHUFFLE(3, 0, 2, 1));
  const __m128 b_zxy = _mm_shuffle_ps(b, b, _MM_SHUFFLE(3, 1, 0, 2));
  return _mm_sub_ps(_mm_mul_ps(a_yzx, b_zxy), _mm_mul_ps(b_yzx, a_zxy));
}

// Normals [begin, count) from their corner lists; normal i's own position is positions[self(i)].
// The vertex's xyz in one register: a corner takes a third of the scalar arithmetic instructions
// (the normals were twice the deformation's time in the CPU runtime), with every lane's value
// rounded as the scalar form below rounds it (no fused multiply-adds in a baseline x86-64 build).
template <typename Self>
void normalsOf(std::span<const std::uint32_t> corner_offsets, std::span<const gpu::Corner> corners,
               std::span<const gpu::Float4> positions, std::span<gpu::Float4> normals, std::size_t begin,
               std::size_t count, Self self) {
  static_assert(sizeof(gpu::Float4) == 4 * sizeof(float));
  const __m128 xyz_mask = _mm_castsi128_ps(_mm_set_epi32(0, -1, -1, -1));
  for (std::size_t i = begin; i < count && i + 1 < corner_offsets.size(); ++i) {
    const __m128 p = _mm_loadu_ps(&positions[self(i)].x);
    __m128 n = _mm_setzero_ps();
    for (std::uint32_t k = corner_offsets[i]; k < corner_offsets[i + 1]; ++k) {
      const gpu::Corner c = corners[k];
      const __m128 a = _mm_sub_ps(_mm_loadu_ps(&positions[c.next].x), p);
      const __m128 b = _mm_sub_ps(_mm_loadu_ps(&positions[c.prev].x), p);
      n = _mm_add_ps(n, cross(a, b));
    }
    // glm::length: sqrt((x x + y y) + z z).
    alignas(16) float sq[4];
    _mm_store_ps(sq, _mm_mul_ps(n, n));
    const float length = std::sqrt((sq[0] + sq[1]) + sq[2]);
    const __m128 unit = length > 0.0f ? _mm_and_ps(_mm_div_ps(n, _mm_set1_ps(length)), xyz_mask) : _mm_setzero_ps();
    _mm_storeu_ps(&normals[i].x, unit);
  }
}

#else

template <typename Self>
void normalsOf(std::span<const std::uint32_t> corner_offsets, std::span<const gpu::Corner> corners,
               std::span<const gpu::Float4> positions, std::span<gpu::Float4> normals, std::size_t begin,
               std::size_t count, Self self) {
  for (std::size_t i = begin; i < count && i + 1 < corner_offsets.size(); ++i) {
    const glm::vec3 p = xyz(positions[self(i)]);
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

#endif

}  // namespace

void computeVertexNormals(std::span<const std::uint32_t> corner_offsets, std::span<const gpu::Corner> corners,
                          std::span<const gpu::Float4> positions, std::span<gpu::Float4> normals,
                          std::size_t begin, std::size_t end) {
  normalsOf(corner_offsets, corners, positions, normals, begin, std::min({positions.size(), normals.size(), end}),
            [](std::size_t i) { return i; });
}

void computeRenderNormals(std::span<const std::uint32_t> corner_offsets, std::span<const gpu::Corner> corners,
                          std::span<const std::uint32_t> topology, std::span<const gpu::Float4> positions,
                          std::span<gpu::Float4> normals, std::size_t begin, std::size_t end) {
  normalsOf(corner_offsets, corners, positions, normals, begin, std::min({topology.size(), normals.size(), end}),
            [topology](std::size_t r) { return topology[r]; });
}

void appendFanTriangles(const FaceList& faces, std::vector<std::uint32_t>& triangles) {
  for (std::size_t f = 0; f < faces.faceCount(); ++f) {
    const std::uint32_t begin = faces.face_offsets[f];
    const std::uint32_t end = faces.face_offsets[f + 1];
    for (std::uint32_t k = begin + 1; k + 1 < end; ++k) {
      triangles.insert(triangles.end(), {faces.indices[begin], faces.indices[k], faces.indices[k + 1]});
    }
  }
}

void buildCorners(const FaceList& faces, std::size_t vertex_count, std::vector<std::uint32_t>& triangles,
                  std::vector<std::uint32_t>& offsets, std::vector<gpu::Corner>& corners) {
  appendFanTriangles(faces, triangles);
  offsets.assign(vertex_count + 1, 0);
  for (std::uint32_t v : triangles) ++offsets[v + 1];
  for (std::size_t i = 0; i < vertex_count; ++i) offsets[i + 1] += offsets[i];
  corners.resize(triangles.size());
  std::vector<std::uint32_t> fill(offsets.begin(), offsets.end() - 1);
  for (std::size_t t = 0; t + 2 < triangles.size(); t += 3) {
    const std::uint32_t a = triangles[t], b = triangles[t + 1], c = triangles[t + 2];
    corners[fill[a]++] = gpu::Corner{b, c};
    corners[fill[b]++] = gpu::Corner{c, a};
    corners[fill[c]++] = gpu::Corner{a, b};
  }
}

void computeVertexNormals(std::span<const std::uint32_t> corner_offsets, std::span<const gpu::Corner> corners,
                          std::span<const gpu::Float4> positions, std::span<gpu::Float4> normals) {
  computeVertexNormals(corner_offsets, corners, positions, normals, 0, normals.size());
}

void gatherRenderVertices(std::span<const std::uint32_t> topology_of_render, std::span<const gpu::Float4> topology,
                          std::span<gpu::Float4> out, std::size_t begin, std::size_t end) {
  for (std::size_t r = begin; r < end; ++r) out[r] = topology[topology_of_render[r]];
}

void InstanceBounds::merge(const InstanceBounds& later) {
  min = glm::min(min, later.min);
  max = glm::max(max, later.max);
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
