// SPDX-License-Identifier: MIT
#include "instance_tangents.hpp"

#include <cmath>
#include <limits>
#include <string>

#include <glm/geometric.hpp>

#include "../core/unit_vector.hpp"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace odeskin {
namespace {

// The in-plane coordinates of an edge in the tangent basis (u, v).
struct PlaneEdge {
  double u;
  double v;
};

// Weights of bind tangent `t` on topology vertex i's corner edges, appended to `out` (one per
// corner). With the one-ring's edges e_j in plane coordinates a_j = (u . e_j, v . e_j), the
// least-squares map F = E' A^T (A A^T)^-1 gives F t = sum_j (a_j . y) e'_j with y = (A A^T)^-1 t_2.
void appendWeights(std::span<const Vec3> rest, std::span<const std::uint32_t> corner_offsets,
                   std::span<const gpu::Corner> corners, std::uint32_t i, const Vec3& t,
                   std::vector<gpu::TangentWeights>& out) {
  const std::uint32_t first = corner_offsets[i];
  const std::uint32_t end = corner_offsets[i + 1];
  const std::size_t zeros_at = out.size();
  out.resize(out.size() + (end - first), gpu::TangentWeights{0.0f, 0.0f});
  Vec3 n(0.0);
  for (std::uint32_t k = first; k < end; ++k) {
    n += glm::cross(rest[corners[k].next] - rest[i], rest[corners[k].prev] - rest[i]);
  }
  const double n_length = glm::length(n);
  if (!(n_length > 0.0) || glm::dot(t, t) == 0.0) return;
  n /= n_length;
  const Vec3 axis = std::fabs(n.x) < 0.9 ? Vec3(1.0, 0.0, 0.0) : Vec3(0.0, 1.0, 0.0);
  const Vec3 u = glm::normalize(axis - n * glm::dot(n, axis));
  const Vec3 v = glm::cross(n, u);
  auto plane = [&](std::uint32_t j) { return PlaneEdge{glm::dot(u, rest[j] - rest[i]), glm::dot(v, rest[j] - rest[i])}; };
  double m00 = 0.0, m01 = 0.0, m11 = 0.0;
  for (std::uint32_t k = first; k < end; ++k) {
    for (const PlaneEdge a : {plane(corners[k].next), plane(corners[k].prev)}) {
      m00 += a.u * a.u;
      m01 += a.u * a.v;
      m11 += a.v * a.v;
    }
  }
  // A one-ring whose edges all lie on one line spans no plane: no map to fit.
  const double det = m00 * m11 - m01 * m01;
  const double trace = m00 + m11;
  if (!(det > 1e-12 * trace * trace)) return;
  const double tu = glm::dot(u, t), tv = glm::dot(v, t);
  const double yu = (m11 * tu - m01 * tv) / det;
  const double yv = (m00 * tv - m01 * tu) / det;
  for (std::uint32_t k = first; k < end; ++k) {
    const PlaneEdge a = plane(corners[k].next), b = plane(corners[k].prev);
    out[zeros_at + (k - first)] = gpu::TangentWeights{static_cast<float>(a.u * yu + a.v * yv),
                                                      static_cast<float>(b.u * yu + b.v * yv)};
  }
}

}  // namespace

Result<TangentLayout> buildTangentLayout(std::span<const Vec3> rest_positions, std::span<const std::uint32_t> corner_offsets,
                                         std::span<const gpu::Corner> corners, std::span<const std::uint32_t> topology,
                                         std::span<const gpu::Float4> tangents) {
  const std::size_t outputs = topology.empty() ? rest_positions.size() : topology.size();
  if (tangents.size() != outputs) {
    return invalidArgument("runtime asset: render tangents: " + std::to_string(tangents.size()) + " tangents for " +
                           std::to_string(outputs) + (topology.empty() ? " vertices" : " render vertices"));
  }
  TangentLayout layout;
  layout.frames.reserve(outputs);
  for (std::size_t o = 0; o < outputs; ++o) {
    const gpu::Float4& t = tangents[o];
    if (!std::isfinite(t.x) || !std::isfinite(t.y) || !std::isfinite(t.z) || !std::isfinite(t.w)) {
      return invalidArgument("runtime asset: render tangents: tangent " + std::to_string(o) + " is not finite");
    }
    // glTF's TANGENT.w "is a sign value (-1 or +1)"; anything else is a different attribute.
    if (std::fabs(std::fabs(t.w) - 1.0f) > 1e-3f) {
      return invalidArgument("runtime asset: render tangents: tangent " + std::to_string(o) + " has w = " + std::to_string(t.w) +
                             "; w is the handedness, +1 or -1");
    }
    const std::uint32_t i = topology.empty() ? static_cast<std::uint32_t>(o) : topology[o];
    if (layout.weights.size() > std::numeric_limits<std::uint32_t>::max()) {
      return outOfRange("runtime asset: render tangents: more than 2^32 corner weights");
    }
    layout.frames.push_back(gpu::TangentFrame{static_cast<std::uint32_t>(layout.weights.size()), t.w < 0.0f ? -1.0f : 1.0f});
    // Only the direction counts; a unit tangent keeps the weights near 1 / edge length, so a
    // tangent given as 1e30 long cannot overflow the frame's float sum into a zero tangent.
    appendWeights(rest_positions, corner_offsets, corners, i, unitVector(Vec3(t.x, t.y, t.z)), layout.weights);
  }
  return layout;
}

#if defined(__SSE2__)

// xyz in one register, as computeVertexNormals does: each lane's value rounded as the scalar form
// below rounds it (products, then sums, in the same order; no fused multiply-adds in a baseline
// x86-64 build). 16 cats' tangents took 2.2 ms a frame on one thread, against 3.0 ms scalar.
void computeVertexTangents(const TangentTables& tables, std::span<const gpu::Float4> positions,
                           std::span<const gpu::Float4> normals, std::span<gpu::Float4> out, std::size_t begin,
                           std::size_t end) {
  static_assert(sizeof(gpu::Float4) == 4 * sizeof(float));
  for (std::size_t o = begin; o < end && o < out.size(); ++o) {
    const std::uint32_t i = tables.topology.empty() ? static_cast<std::uint32_t>(o) : tables.topology[o];
    const gpu::TangentFrame frame = tables.frames[o];
    const __m128 p = _mm_loadu_ps(&positions[i].x);
    __m128 t = _mm_setzero_ps();
    const std::uint32_t first = tables.corner_offsets[i];
    for (std::uint32_t k = first; k < tables.corner_offsets[i + 1]; ++k) {
      const gpu::Corner c = tables.corners[k];
      const gpu::TangentWeights w = tables.weights[frame.weights + (k - first)];
      const __m128 a = _mm_mul_ps(_mm_set1_ps(w.next), _mm_sub_ps(_mm_loadu_ps(&positions[c.next].x), p));
      const __m128 b = _mm_mul_ps(_mm_set1_ps(w.prev), _mm_sub_ps(_mm_loadu_ps(&positions[c.prev].x), p));
      t = _mm_add_ps(t, _mm_add_ps(a, b));
    }
    // glm::dot and glm::length: (x x' + y y') + z z'. The w lanes are never read.
    const __m128 n = _mm_loadu_ps(&normals[o].x);
    alignas(16) float nt[4];
    _mm_store_ps(nt, _mm_mul_ps(n, t));
    t = _mm_sub_ps(t, _mm_mul_ps(n, _mm_set1_ps((nt[0] + nt[1]) + nt[2])));
    alignas(16) float sq[4];
    _mm_store_ps(sq, _mm_mul_ps(t, t));
    const float length = std::sqrt((sq[0] + sq[1]) + sq[2]);
    alignas(16) float unit[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    if (length > 0.0f) _mm_store_ps(unit, _mm_div_ps(t, _mm_set1_ps(length)));
    out[o] = gpu::Float4{unit[0], unit[1], unit[2], frame.handedness};
  }
}

#else

namespace {
glm::vec3 xyz(const gpu::Float4& f) { return {f.x, f.y, f.z}; }
}  // namespace

void computeVertexTangents(const TangentTables& tables, std::span<const gpu::Float4> positions,
                           std::span<const gpu::Float4> normals, std::span<gpu::Float4> out, std::size_t begin,
                           std::size_t end) {
  for (std::size_t o = begin; o < end && o < out.size(); ++o) {
    const std::uint32_t i = tables.topology.empty() ? static_cast<std::uint32_t>(o) : tables.topology[o];
    const gpu::TangentFrame frame = tables.frames[o];
    const glm::vec3 p = xyz(positions[i]);
    glm::vec3 t(0.0f);
    const std::uint32_t first = tables.corner_offsets[i];
    for (std::uint32_t k = first; k < tables.corner_offsets[i + 1]; ++k) {
      const gpu::Corner c = tables.corners[k];
      const gpu::TangentWeights w = tables.weights[frame.weights + (k - first)];
      t += w.next * (xyz(positions[c.next]) - p) + w.prev * (xyz(positions[c.prev]) - p);
    }
    const glm::vec3 n = xyz(normals[o]);
    t -= n * glm::dot(n, t);
    const float length = glm::length(t);
    t = length > 0.0f ? t / length : glm::vec3(0.0f);
    out[o] = gpu::Float4{t.x, t.y, t.z, frame.handedness};
  }
}

#endif

}  // namespace odeskin
