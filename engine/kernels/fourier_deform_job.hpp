// SPDX-License-Identifier: MIT
// CPU reference kernel (double): analytic skin deformation of every vertex at one frame.
// Thesis Eq 6.30 (corrected, MATH.md 5.6) composed with skinning as PIPELINE.md section 3 says:
//   D_i(tau) = (1 - w) S_a(v) + w S_b(v),  S_c(v) = sum_m [gamma_n(m) d_cm + psi_n(m) rdot_cm] phi_m(v)
//   bind:  out_i = sum_b w_ib M_b (X_i + r_i^s + D_i(tau) + gamma_0(tau) eps_i)
//   posed: out_i = sum_b w_ib M_b X_i + r_i^s + D_i(tau) + gamma_0(tau) eps_i
// where `sum_b w_ib M_b x` is linear blend skinning, or, with SkinningMode::kDualQuaternion, the
// vertex's blended rigid transform (Kavan et al. 2008; skinTransform in dual_quaternion.hpp).
// with phi_m the MATH.md 4.2 basis plus the open-curve trend phi_{2N+1}(v) = v (mode 0), eps_i the
// sparse remainder (PIPELINE.md 4) following mode 0 of curve_a's material. Mirrored by
// fourier_deform_fast_job (float) and shaders/fourier_deform.comp.
#pragma once

#include <cstdint>
#include <span>

#include "../core/status.hpp"
#include "../core/types.hpp"
#include "influences.hpp"

namespace odeskin {

inline constexpr std::uint32_t kNoRemainder = 0xFFFFFFFFu;

// Coefficients per curve for N modes: 2N+1 Fourier terms and the open-curve trend.
constexpr std::size_t coefficientsPerCurve(int modes) { return 2 * static_cast<std::size_t>(modes) + 2; }

// S_c(v) of curve `curve`: sum_m [gamma_n(m) d_cm + psi_n(m) rdot_cm] phi_m(v) (the gpu_layout.h
// coefficient layout), with `material_basis` the N+1 values of the curve's material. `rates` may
// be empty (zero). Reference precision: cos/sin evaluated directly for every harmonic.
Vec3 curveSeries(std::span<const Vec3> coefficients, std::span<const Vec3> rates,
                 std::span<const ModeBasisValue> material_basis, int modes, std::uint32_t curve, double v);

struct FourierDeformJob {
  int modes = 0;  // N, 1..64
  ResidualSpace residual_space = ResidualSpace::kBind;
  SkinningMode skinning = SkinningMode::kLinear;  // kDualQuaternion: bones are taken as rigid

  std::span<const Vec3> rest_positions;          // V, required: bind mesh X
  std::span<const CurveBinding> bindings;        // V, required
  std::span<const Vec3> base_residuals;          // V, or empty for zero: r^s of the segment's start
  std::span<const std::uint32_t> remainder_indices;  // V, or empty: index into remainders or kNoRemainder
  std::span<const Vec3> remainders;              // sparse remainders eps referenced above
  std::span<const std::uint32_t> curve_materials;    // C, required: material index of each curve
  std::span<const Vec3> coefficients;            // C * (2N+2), required: d_cm of the segment
  std::span<const Vec3> rates;                   // C * (2N+2), or empty for zero: rdot_cm
  // material_count * (N+1), required: entry [material * (N+1) + n] holds gamma_n, psi_n at tau.
  std::span<const ModeBasisValue> basis;
  InfluencesView influences;                     // V rows, required
  std::span<const BoneTransform> bones;          // B, required: M_b(tau)
  std::span<Vec3> out_positions;                 // V, required

  // kInvalidArgument naming the first field that breaks its contract (sizes, curve or material or
  // bone or remainder index out of range, w outside [0, 1], non-finite basis value or bone, unknown
  // skinning mode);
  // kOutOfRange for N outside 1..64.
  Status validate() const;
  // validate(), then writes out_positions.
  Status run() const;
};

}  // namespace odeskin
