// SPDX-License-Identifier: MIT
// Synthetic PackedDeformData for CPU/GPU parity: random curves, bindings, coefficients, rates,
// sparse remainders and influences, built directly in the GPU layout (no fitting involved). Used by
// the CPU kernel test and the GPU deformer test. The bone and basis generators are named randomGpu*
// so that they do not collide with test_meshes.hpp's randomBones/randomBasis (engine types).
#pragma once

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

#include "engine/kernels/packed_deform.hpp"

namespace odeskin::testing {

struct RandomPackedOptions {
  std::uint32_t vertex_count = 100;
  std::uint32_t influence_layout = ODESKIN_INFLUENCES_SPARSE;  // 0, 4 or 8
  ResidualSpace residual_space = ResidualSpace::kBind;
  bool rates = true;
  std::uint32_t seed = 1;
  SkinningMode skinning = SkinningMode::kLinear;
  std::uint32_t modes = 3;
  std::uint32_t curve_count = 5;
  std::uint32_t segment_count = 2;
  // One binding in four sits exactly on a curve end (w = 0 or w = 1) instead of inside.
  bool w_edge_cases = false;
  // This segment carries no sparse remainder at all (kNoSegment: every segment may).
  std::uint32_t segment_without_remainders = kNoSegment;
  // Every third curve has zero coefficients past n = 2 (curves of lower order than the asset).
  bool truncate_every_third_curve = false;

  static constexpr std::uint32_t kNoSegment = ~0u;
};

inline PackedDeformData randomPackedData(const RandomPackedOptions& o) {
  std::mt19937 rng(o.seed);
  auto uniform = [&](float lo, float hi) { return std::uniform_real_distribution<float>(lo, hi)(rng); };
  auto below = [&](std::uint32_t n) { return std::uniform_int_distribution<std::uint32_t>(0, n - 1)(rng); };
  PackedDeformData d;
  d.vertex_count = o.vertex_count;
  d.modes = o.modes;
  d.curve_count = o.curve_count;
  d.material_count = 2;
  d.bone_count = 7;
  d.segment_count = o.segment_count;
  d.influence_layout = o.influence_layout;
  d.residual_space = o.residual_space;
  d.skinning = o.skinning;
  const std::uint32_t v_count = d.vertex_count;
  const std::uint32_t m = d.coefficientsPerCurve();

  for (std::uint32_t i = 0; i < v_count; ++i) {
    d.rest_positions.push_back({uniform(-1, 1), uniform(-1, 1), uniform(-1, 1), 0.0f});
    // The draws keep their order (w before or after the curve pair) so that a seed gives the same data.
    const std::uint32_t pick = o.w_edge_cases ? below(8) : 2;
    float w = pick == 0 ? 0.0f : (pick == 1 ? 1.0f : (o.w_edge_cases ? uniform(0, 1) : 0.0f));
    const std::uint32_t first = below(d.curve_count);
    const std::uint32_t second = below(d.curve_count);
    if (!o.w_edge_cases) w = uniform(0, 1);
    d.bindings.push_back({first, second, w, uniform(0, 0.999f)});
  }
  // About a third of the vertices carry a sparse remainder in each segment.
  for (std::uint32_t s = 0; s < d.segment_count; ++s) {
    d.remainder_base.push_back(static_cast<std::uint32_t>(d.remainders.size()));
    std::uint32_t local = 0;
    for (std::uint32_t i = 0; i < v_count; ++i) {
      gpu::SegmentVertex sv{uniform(-0.05f, 0.05f), uniform(-0.05f, 0.05f), uniform(-0.05f, 0.05f),
                            gpu::kNoRemainder};
      if (s != o.segment_without_remainders && below(3) == 0) {
        sv.remainder_index = local++;
        d.remainders.push_back({uniform(-0.02f, 0.02f), uniform(-0.02f, 0.02f), uniform(-0.02f, 0.02f), 0.0f});
      }
      d.segment_vertices.push_back(sv);
    }
  }
  for (std::uint32_t c = 0; c < d.curve_count; ++c) d.curve_materials.push_back(below(d.material_count));
  for (std::uint32_t k = 0; k < d.segment_count * d.curve_count * m; ++k) {
    const std::uint32_t term = k % m;
    const bool zero = o.truncate_every_third_curve && (k / m) % 3 == 0 && term > 4 && term + 1 < m;
    const float scale = zero ? 0.0f : 1.0f;
    d.coefficients.push_back(
        {scale * uniform(-0.1f, 0.1f), scale * uniform(-0.1f, 0.1f), scale * uniform(-0.1f, 0.1f), 0.0f});
    if (o.rates) {
      d.rates.push_back({scale * uniform(-0.1f, 0.1f), scale * uniform(-0.1f, 0.1f), scale * uniform(-0.1f, 0.1f), 0.0f});
    }
  }

  // 1 to 6 influences per vertex (at most the slot count), weights summing to 1.
  const std::uint32_t max_influences = o.influence_layout == 0 ? 6 : std::min<std::uint32_t>(6, o.influence_layout);
  if (o.influence_layout == ODESKIN_INFLUENCES_SPARSE) d.influence_offsets.push_back(0);
  for (std::uint32_t i = 0; i < v_count; ++i) {
    const std::uint32_t count = 1 + below(max_influences);
    std::vector<gpu::Influence> row;
    float sum = 0.0f;
    for (std::uint32_t k = 0; k < count; ++k) {
      row.push_back({below(d.bone_count), uniform(0.05f, 1.0f)});  // repeated bones allowed
      sum += row.back().weight;
    }
    for (gpu::Influence& inf : row) inf.weight /= sum;
    if (o.influence_layout != ODESKIN_INFLUENCES_SPARSE) row.resize(o.influence_layout, gpu::Influence{0, 0.0f});
    d.influences.insert(d.influences.end(), row.begin(), row.end());
    if (o.influence_layout == ODESKIN_INFLUENCES_SPARSE) {
      d.influence_offsets.push_back(static_cast<std::uint32_t>(d.influences.size()));
    }
  }
  return d;
}

// Affine bones near the identity (rotation-ish plus shear plus translation). Dual-quaternion
// skinning takes their nearest rotations (toGpuDualQuaternions).
inline std::vector<gpu::BoneMatrix> randomGpuBones(std::uint32_t count, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-0.3f, 0.3f);
  std::vector<gpu::BoneMatrix> bones;
  for (std::uint32_t b = 0; b < count; ++b) {
    bones.push_back({{1 + u(rng), u(rng), u(rng), u(rng)}, {u(rng), 1 + u(rng), u(rng), u(rng)},
                     {u(rng), u(rng), 1 + u(rng), u(rng)}});
  }
  return bones;
}

inline std::vector<gpu::ModeBasis> randomGpuBasis(std::size_t count, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<gpu::ModeBasis> basis;
  for (std::size_t k = 0; k < count; ++k) basis.push_back({u(rng), u(rng)});
  return basis;
}

}  // namespace odeskin::testing
