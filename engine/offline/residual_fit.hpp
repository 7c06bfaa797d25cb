// SPDX-License-Identifier: MIT
// From example poses to a DeformAsset (PIPELINE.md 2-4; thesis ch. 6 with MATH.md 4.4's shared-v fit):
//   r_i^k = (A_i^k)^{-1} (P_{k,i} - L_k(X_i))        exact bind-space corrective of key k
//   Delta^s = r^{s+1} - r^s, fitted per iso-curve by a Fourier series in v (N modes)
//   eps_i = Delta_i^s - [(1-w) S_a(v) + w S_b(v)] kept sparsely where it exceeds the key tolerance
//   rdot^s = gamma_n'(1) d^{s-1} + psi_n'(1) rdot^{s-1}  (rate continuity across keys, MATH.md 5.2)
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "../core/iso_curve.hpp"
#include "../core/result.hpp"
#include "deform_asset.hpp"

namespace odeskin {

struct FitInput {
  std::vector<Vec3> rest_positions;                  // V: bind mesh X
  FaceList faces;
  std::vector<std::vector<Vec3>> poses;              // K x V example poses
  Influences influences;
  std::uint32_t bone_count = 0;
  std::vector<Vec3> bone_pivots;                     // B
  std::vector<std::vector<RigidTransform>> key_poses;  // K x B, bind -> pose k
  std::vector<IsoCurve> curves;                      // C: points on the bind mesh, each with its v
  std::vector<CurveBinding> bindings;                // V
};

struct FitOptions {
  int modes = 9;
  ResidualSpace residual_space = ResidualSpace::kBind;
  SkinningMode skinning = SkinningMode::kLinear;
  std::vector<Material> materials;                   // empty: one static material
  std::vector<std::uint32_t> curve_materials;        // C, or empty: every curve uses material 0
  // Key poses are reproduced within key_tolerance x (longest bounding-box side of the pose) by
  // sparse remainders, unless pure_fourier (the thesis's representation, error only reported).
  double key_tolerance = 1e-4;
  bool pure_fourier = false;
  // A curve with too few points (or too uneven a spacing) for N modes is fitted with the largest
  // N' < N its points determine (PIPELINE.md 4's per-curve N); false makes that an error.
  bool adaptive_modes = true;
};

struct FitReport {
  std::vector<double> key_error;      // K: max vertex error of the played key / longest box side
  std::size_t remainder_count = 0;    // sparse remainders over all segments
  // Vertices whose blended linear part A was near singular at some key (LBS mixing nearly opposed
  // rotations), rebound rigidly to their dominant bone so A^-1 stays well conditioned.
  std::size_t ill_conditioned = 0;
  double max_series_error = 0.0;      // worst |eps| before remainders, / longest box side
  double rms_series_error = 0.0;      // root mean square |eps| over all vertices and segments, / box side
  std::size_t reduced_curves = 0;     // (segment, curve) fits that used fewer than N modes
  // Seconds per stage (thesis Table 6.3): conditioning the blended linear parts, skinning the bind
  // mesh at every key and the bind-space residuals; Fourier fits and remainders; time bases, rate
  // chaining and playing every key back.
  double seconds_geometric = 0.0;
  double seconds_fourier = 0.0;
  double seconds_solve = 0.0;
};

// Errors: kInvalidArgument (sizes, indices, a curve point off the mesh or without its v, fewer
// than 2 poses, a pose or the bind mesh with a position that is not finite, or too large or
// small for double-precision lengths: checkedPositionBox), kIllPosed (a curve with too few points
// for N when !adaptive_modes, a resonant material mode), kOutOfRange (a key played back off by
// more than the key tolerance, or by a non-finite amount: magnitudes beyond double precision
// beside the mesh's size), and the errors of fitFourier / ModeTimeBasis::create, each prefixed
// with the curve or material concerned.
Result<DeformAsset> fitDeformAsset(const FitInput& input, const FitOptions& options, FitReport* report = nullptr);

// Recomputes every segment's carried rates from its predecessor with the asset's current materials
// (PIPELINE.md 3: rdot^s = gamma_n'(1) d^{s-1} + psi_n'(1) rdot^{s-1}, rdot^0 = 0), e.g. after
// replacing the materials of a fitted asset. Errors: those of DeformPlayer::create.
Status chainSegmentRates(DeformAsset& asset);

// Longest side of the axis-aligned bounding box (MATH.md 6.1's Lbox).
double longestBoxSide(std::span<const Vec3> positions);

}  // namespace odeskin
