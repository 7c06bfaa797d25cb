// SPDX-License-Identifier: MIT
// Least-squares Fourier representation of iso-parametric curves (MATH.md 4.1-4.3; thesis Eqs
// 6.2-6.9, corrected by G9, G10). Basis order, fixed everywhere: phi_0 = 1, phi_{2n-1} = cos(2 pi n v),
// phi_{2n} = sin(2 pi n v), n = 1..N.
#pragma once

#include <memory>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "../core/result.hpp"

namespace odeskin {

inline constexpr int kMaxFourierModes = 64;

// Normalised arc-length parameters (MATH.md 4.1). Closed: J distinct points, the closing segment
// P_{J-1} -> P_0 counts, v_0 = 0 and every v_j < 1. Open: P_0..P_J, v_0 = 0, v_J = 1.
// Errors: kInvalidArgument for fewer than 2 points or non-finite coordinates; kDegenerate when the
// total length is 0.
Result<std::vector<double>> arcLengthParameters(std::span<const glm::dvec3> points, bool closed);

// phi_m(v) for m = 0..2N into `out` (size >= 2N+1).
void fourierBasis(double v, int modes, std::span<double> out);

struct FourierFit {
  int modes = 0;      // N
  bool closed = true;
  // 2N+1 coefficients in basis order. Open curves: coefficients[0] = -sum_n coefficients[2n-1], so
  // that C(0) = p0 and C(1) = p0 + slope in exact arithmetic; in floating point to about eps x the
  // largest cosine coefficient (1.7e-10 off for a fit of condition 1e10, where the sum cancels).
  std::vector<glm::dvec3> coefficients;
  glm::dvec3 p0{0.0};     // open curves only: P_0
  glm::dvec3 slope{0.0};  // open curves only: P_J - P_0
  double rss = 0.0;       // residual sum of squares over all samples and coordinates

  // C(v) = [p0 + slope v] + sum_m coefficients[m] phi_m(v).
  glm::dvec3 evaluate(double v) const;
};

// Fits `values` sampled at parameters `v` (same length) with N modes, 1 <= N <= kMaxFourierModes,
// by Householder QR (Eigen). Closed: all samples. Open: the first and last samples are interpolated
// by the trend p0 + slope v, the interior samples by least squares (MATH.md 4.3).
// Errors: kOutOfRange for N outside [1, kMaxFourierModes]; kInvalidArgument for mismatched sizes or
// non-finite input; kIllPosed when the design matrix is rank deficient (min|R_ii| <= 1e-10 max|R_ii|;
// e.g. fewer than 2N+1 samples, or the uniform J = 2N Nyquist case).
Result<FourierFit> fitFourier(std::span<const double> v, std::span<const glm::dvec3> values, int modes,
                              bool closed);

// fitFourier split in two for many value sets on the same parameters (one curve, every segment of a
// fit): the design matrix depends on v alone, so it is factorised once. fit(values) returns what
// fitFourier(v, values, modes, closed) returns, bit for bit.
class FourierFitter {
 public:
  // The checks of fitFourier that concern v, N and the sample count, then the factorisation.
  // Errors: as fitFourier's, except those about `values`.
  static Result<FourierFitter> create(std::span<const double> v, int modes, bool closed);
  // `values`: one per parameter. kInvalidArgument for a size mismatch or a non-finite value.
  Result<FourierFit> fit(std::span<const glm::dvec3> values) const;

  int modes() const { return modes_; }
  bool closed() const { return closed_; }

 private:
  struct Design;
  FourierFitter() = default;
  std::vector<double> v_;
  int modes_ = 0;
  bool closed_ = true;
  std::shared_ptr<const Design> design_;  // the factorised matrix (shared: copies are cheap)
};

}  // namespace odeskin
