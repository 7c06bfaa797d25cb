// SPDX-License-Identifier: MIT
// The curve-based finite-difference dynamic deformation (thesis 5.5) as an in-between method on a
// fitted DeformAsset: the same curves, bindings, bind-space correctives r^s and remainders as
// odeskin, but each segment's residual motion along every iso-curve comes from the space-time
// finite-difference solve of FdCurveSystem instead of the analytic per-mode time basis.
//
// Per segment s and curve c, the target is the fitted Delta^s on the curve (MATH.md 4.3 layout):
// its periodic part sum_{m <= 2N} d_m phi_m(v), sampled at v_j = j / J, is solved on the periodic
// grid; an open curve's linear trend slope * v (on which u_vv vanishes, the analytic method's
// mode-0 treatment) is solved by the same scheme with J = 1. The rate carried into segment s > 0 is
// the FD solution's own end rate of segment s - 1 (FdCurveSystem::endRates); segment 0 starts at
// rest. Each solved time level is mapped back to Fourier coefficients by the discrete Fourier
// transform of the grid (exact for the N modes when J > 2N, since the periodic difference operator
// keeps modes apart), so vertices are evaluated through the same (curve_a, curve_b, w, v) bindings
// and kernel (FourierDeformJob) as odeskin. Playback at tau interpolates the levels linearly in t
// (second order, like the scheme). At tau = 1 the level is Delta^s exactly, so the keys are
// reproduced as well as odeskin reproduces them.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "../core/result.hpp"
#include "../offline/deform_asset.hpp"
#include "../offline/material.hpp"
#include "baseline.hpp"
#include "baseline_rig.hpp"

namespace odeskin {

struct FdCurveOptions {
  std::uint32_t points = 32;         // J per curve (periodic grid), > 2N
  std::uint32_t steps = 32;          // T per segment, >= 2
  std::optional<Material> material;  // every curve's material; nullopt: the asset's own
};

// Set-up cost, for the thesis Table 6.1 comparison (frames per second of FD vs analytic): the
// factorisations and solves happen once per asset, playback is an interpolation plus the kernel.
struct FdCurveStats {
  double seconds_factor = 0.0;       // SparseLU factorisations (one per material and grid size)
  double seconds_solve = 0.0;        // every (segment, curve) space-time solve and its DFT
  std::size_t factorizations = 0;
  std::size_t curve_solves = 0;      // (segment, curve) pairs, each with 3 coordinates
  std::size_t unknowns_per_system = 0;  // J T
};

class FdCurveDeformer final : public Baseline {
 public:
  // Errors: kInvalidArgument (J <= 2N, T < 2, an invalid asset), and those of FdCurveSystem
  // (degenerate or singular material) prefixed with the material and curve.
  static Result<FdCurveDeformer> create(const DeformAsset& asset, const FdCurveOptions& options = {});

  BaselineMethod method() const override { return BaselineMethod::kFdCurve; }
  Status evaluate(const BaselineFrameInput& frame, std::span<Vec3> out) override;

  const FdCurveStats& stats() const { return stats_; }
  std::uint32_t steps() const { return steps_; }
  // Coefficients of every curve at time level n (0..T) of `segment`: C x (2N+2) in the asset's layout.
  std::span<const Vec3> levelCoefficients(std::uint32_t segment, std::uint32_t n) const;

 private:
  FdCurveDeformer(DeformAsset asset, BaselineRig rig);

  DeformAsset asset_;
  BaselineRig rig_;
  std::uint32_t steps_ = 0;
  FdCurveStats stats_;
  std::vector<std::vector<Vec3>> levels_;  // per segment: (T + 1) x C x (2N+2)
  std::vector<Vec3> coefficients_;          // scratch: C x (2N+2) at the frame's tau
  std::vector<ModeBasisValue> basis_;       // scratch: every gamma 1, then the remainder weight
  std::vector<BoneTransform> bones_;        // keys protocol scratch
};

}  // namespace odeskin
