// SPDX-License-Identifier: MIT
// The analytic deformation of a DeformAsset as morph targets (PIPELINE.md 3; the reference kernel's
// bind-space residual, fourier_deform_job.hpp). Within segment s at tau the kernel adds
//   r^s + sum_{m,n} [gamma_{m,n}(tau) G_{s,m,n} + psi_{m,n}(tau) P_{s,m,n}] + w_r(tau) eps^s
// where G_{s,m,n} is the series of segment s's coefficients restricted to mode n of the curves of
// material m, blended (1-w)/w between each vertex's two curves exactly as the kernel blends them,
// P_{s,m,n} the same of the rates, eps^s the sparse remainder and w_r = 3 tau^2 - 2 tau^3. Every
// field is one target whose weight follows its time basis during segment s, is 0 before it and
// holds its value at tau = 1 after it, so the targets of all played segments add up (telescoping).
// Per-curve materials are exact: each material has its own targets. Fields whose weight curves are
// identical (every mode of a static material follows gamma = tau) are summed into one target.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "../core/result.hpp"
#include "../offline/deform_player.hpp"

namespace odeskin {

enum class WeightCurveKind {
  kGamma,      // gamma_n(tau) of one (material, mode)
  kPsi,        // psi_n(tau) of one (material, mode), the response to the carried rate
  kRemainder,  // 3 tau^2 - 2 tau^3 (remainderWeight), the key correction E_s
};

struct WeightCurveSample {
  double value = 0.0;
  double derivative = 0.0;  // d / d tau
};

// The weight of a target during its segment, tau in [0, 1].
struct WeightCurve {
  WeightCurveKind kind = WeightCurveKind::kRemainder;
  std::optional<ModeTimeBasis> basis;  // set for kGamma and kPsi
  WeightCurveSample at(double tau) const;
};

// A displacement field on some topology vertices (increasing indices, no exact zeros stored).
struct SparseField {
  std::vector<std::uint32_t> vertices;
  std::vector<Vec3> values;
  double maxLength() const;
};

struct ModeTarget {
  std::uint32_t segment = 0;
  std::string name;  // e.g. "s0.gamma.m0.n1-9", "s1.psi.m0.n2", "s0.key", "s2.remainder"
  WeightCurve curve;
  SparseField field;  // bind space, at weight 1
};

struct ModeTargetSet {
  std::vector<ModeTarget> targets;  // grouped by segment, in segment order
  std::size_t merged_fields = 0;    // (material, mode) fields summed into another with the same curve
  std::size_t zero_fields = 0;      // fields left out because they are zero everywhere
  // Mid-segment deviation from the player: the key correction E_s = r^{s+1} - r^s - series_s(1) of
  // every segment but the last replaces the sparse remainder eps^s, so the export reproduces
  // r^{s+1} exactly at every key while the player, at tau -> 1, misses it by |E_s - eps_s| (below
  // half the fit's key tolerance where it stored no remainder). This is max_i |E_s,i - eps_s,i| over
  // those segments (bind space, absolute); the posed deviation is at most w_r(tau) times it.
  double max_player_deviation = 0.0;
};

struct ModeTargetOptions {
  // Keep every segment's key correction even where it moves no vertex (an empty field): the
  // NORMAL deltas (target_normals.hpp) need one per segment to land exactly on each key's normals.
  bool keep_zero_corrections = false;
};

// kInvalidArgument for a posed-space residual (glTF adds morph targets before skinning only).
Result<ModeTargetSet> buildModeTargets(const DeformAsset& asset, const DeformPlayer& player,
                                       const ModeTargetOptions& options = {});

}  // namespace odeskin
