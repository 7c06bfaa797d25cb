// SPDX-License-Identifier: MIT
// Random but reproducible deformer data for kernel tests (fixed seeds: failures replay exactly).
#pragma once

#include <random>
#include <vector>

#include "engine/kernels/fourier_deform_job.hpp"
#include "engine/offline/deform_asset.hpp"

namespace odeskin::testing {

// A DeformAsset with `vertices` vertices, `curves` curves, N = `modes`, 2 segments, `materials`
// materials, up to `max_influences` influences per vertex over `bones` bones, sparse remainders on
// about a tenth of the vertices, non-zero rates in segment 1.
inline DeformAsset randomAsset(std::size_t vertices, std::uint32_t curves, int modes, std::uint32_t bones,
                               std::uint32_t max_influences, std::uint32_t materials, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_real_distribution<double> positive(0.0, 1.0);
  auto vec = [&](double scale) { return scale * Vec3(unit(rng), unit(rng), unit(rng)); };
  DeformAsset a;
  a.modes = modes;
  a.rest_positions.resize(vertices);
  for (Vec3& x : a.rest_positions) x = vec(1.0);
  a.bindings.resize(vertices);
  for (CurveBinding& b : a.bindings) {
    b.curve_a = static_cast<std::uint32_t>(rng() % curves);
    b.curve_b = rng() % 3 == 0 ? b.curve_a : static_cast<std::uint32_t>(rng() % curves);
    b.w = b.curve_a == b.curve_b ? 0.0 : positive(rng);
    b.v = positive(rng) * 0.999;
  }
  a.curve_materials.resize(curves);
  for (std::uint32_t& m : a.curve_materials) m = static_cast<std::uint32_t>(rng() % materials);
  a.materials.assign(materials, Material{});
  a.bone_count = bones;
  a.bone_pivots.assign(bones, Vec3(0.0));
  a.influences.offsets.assign(1, 0);
  for (std::size_t i = 0; i < vertices; ++i) {
    const std::uint32_t count = 1 + static_cast<std::uint32_t>(rng() % std::min(max_influences, bones));
    std::vector<double> w(count);
    double sum = 0.0;
    for (double& x : w) sum += (x = 0.05 + positive(rng));
    const std::uint32_t first = static_cast<std::uint32_t>(rng() % bones);
    for (std::uint32_t k = 0; k < count; ++k) {
      a.influences.bones.push_back((first + k) % bones);
      a.influences.weights.push_back(w[k] / sum);
    }
    a.influences.offsets.push_back(static_cast<std::uint32_t>(a.influences.bones.size()));
  }
  a.key_poses.assign(3, std::vector<RigidTransform>(bones));
  const std::size_t m_count = coefficientsPerCurve(modes);
  a.segments.resize(2);
  for (std::size_t s = 0; s < 2; ++s) {
    DeformSegment& seg = a.segments[s];
    seg.base_residuals.resize(vertices);
    for (Vec3& r : seg.base_residuals) r = vec(0.05);
    seg.coefficients.resize(curves * m_count);
    for (std::size_t k = 0; k < seg.coefficients.size(); ++k) {
      seg.coefficients[k] = vec(0.1 / (1.0 + static_cast<double>(k % m_count)));
    }
    seg.rates.assign(curves * m_count, Vec3(0.0));
    if (s == 1) {
      for (Vec3& r : seg.rates) r = vec(0.05);
    }
    seg.remainder_indices.assign(vertices, kNoRemainder);
    for (std::size_t i = 0; i < vertices; ++i) {
      if (rng() % 10 == 0) {
        seg.remainder_indices[i] = static_cast<std::uint32_t>(seg.remainders.size());
        seg.remainders.push_back(vec(0.01));
      }
    }
  }
  return a;
}

// Random rigid bone transforms (rotation angle up to ~1 rad, translation up to 0.5).
inline std::vector<BoneTransform> randomBones(std::uint32_t bones, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<BoneTransform> out(bones);
  for (BoneTransform& b : out) {
    const Vec3 axis = glm::normalize(Vec3(unit(rng), unit(rng), unit(rng)) + Vec3(0.0, 0.0, 1e-3));
    RigidTransform r;
    r.rotation = glm::angleAxis(unit(rng), axis);
    r.translation = 0.5 * Vec3(unit(rng), unit(rng), unit(rng));
    b = r.matrix();
  }
  return out;
}

inline std::vector<ModeBasisValue> randomBasis(std::size_t count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.5);
  std::vector<ModeBasisValue> out(count);
  for (ModeBasisValue& b : out) b = ModeBasisValue{unit(rng), 0.3 * unit(rng)};
  return out;
}

}  // namespace odeskin::testing
