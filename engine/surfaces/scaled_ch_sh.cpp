// SPDX-License-Identifier: MIT
#include "scaled_ch_sh.hpp"

#include <cmath>

namespace odeskin {
namespace {

// Below 1e-3 the three-term series of sinh(y)/y and sin(z)/z is exact to ~1e-19 relative; above it
// the quotient of the library functions loses no more than an ulp or two.
constexpr double kSeriesArgument = 1e-3;

double sinhc(double y) {
  if (std::fabs(y) < kSeriesArgument) {
    const double y2 = y * y;
    return 1.0 + y2 / 6.0 * (1.0 + y2 / 20.0);
  }
  return std::sinh(y) / y;
}

double sinc(double z) {
  if (std::fabs(z) < kSeriesArgument) {
    const double z2 = z * z;
    return 1.0 - z2 / 6.0 * (1.0 - z2 / 20.0);
  }
  return std::sin(z) / z;
}

}  // namespace

ScaledChSh scaledChSh(double x, double t) {
  if (x == 0.0) return {1.0, t};
  if (x < 0.0) {
    const double q = std::sqrt(-x);
    return {std::cos(q * t), t * sinc(q * t)};
  }
  // MATH.md 1.4: cosh(p a)/cosh(p/2) = e^{p(a - 1/2)} (1 + e^{-2pa}) / (1 + e^{-p}) with a = |t|;
  // every factor is at most 1 (for a <= 1/2), so nothing overflows even for p in the thousands.
  const double p = std::sqrt(x);
  const double a = std::fabs(t);
  const double den = 1.0 + std::exp(-p);
  const double grow = std::exp(p * (a - 0.5));
  ScaledChSh out;
  out.ch = grow * (1.0 + std::exp(-2.0 * p * a)) / den;
  if (p * a < kSeriesArgument) {
    const double inv_n = 2.0 * std::exp(-0.5 * p) / den;  // 1/cosh(p/2)
    out.sh = t * sinhc(p * a) * inv_n;
  } else {
    out.sh = std::copysign(grow * -std::expm1(-2.0 * p * a) / (den * p), t);
  }
  return out;
}

}  // namespace odeskin
