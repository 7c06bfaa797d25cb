// SPDX-License-Identifier: MIT
#include "series_functions.hpp"

#include <cmath>

namespace odeskin {

namespace {

// Below |w| = 1 the series converge like 1/n!, so 20 terms leave a remainder < 1e-40; above it the
// closed forms lose at most a few ulps to cancellation (e.g. e^x - 1 - x at |x| = 1 keeps 0.37).
constexpr double kSeriesLimit = 1.0;
constexpr int kSeriesTerms = 20;

}  // namespace

ChSh chSh(double x, double t) {
  const double w = x * t * t;
  if (std::fabs(w) <= kSeriesLimit) {
    // Summed from the smallest term up so the rounding of the large leading terms comes last.
    double ch = 0.0;
    double sh = 0.0;
    for (int k = kSeriesTerms; k >= 1; --k) {
      const double two_k = 2.0 * k;
      ch = w / ((two_k - 1.0) * two_k) * (1.0 + ch);
      sh = w / (two_k * (two_k + 1.0)) * (1.0 + sh);
    }
    return {1.0 + ch, t * (1.0 + sh)};
  }
  if (x > 0.0) {
    const double p = std::sqrt(x);
    return {std::cosh(p * t), std::sinh(p * t) / p};
  }
  const double omega = std::sqrt(-x);
  return {std::cos(omega * t), std::sin(omega * t) / omega};
}

double phi1(double x) {
  if (std::fabs(x) < kSeriesLimit) {
    // phi1(x) = sum x^k/(k+1)!, in Horner form.
    double s = 0.0;
    for (int k = kSeriesTerms; k >= 1; --k) s = x / (k + 1.0) * (1.0 + s);
    return 1.0 + s;
  }
  return std::expm1(x) / x;
}

double phi2(double x) {
  if (std::fabs(x) < kSeriesLimit) {
    // phi2(x) = sum x^k/(k+2)!, in Horner form.
    double s = 0.0;
    for (int k = kSeriesTerms; k >= 1; --k) s = x / (k + 2.0) * (1.0 + s);
    return 0.5 * (1.0 + s);
  }
  // e^x/x^2 once e^x overflows but the quotient does not (and x*x would reach inf first).
  if (x > 700.0) return std::exp(x - 2.0 * std::log(x));
  return (std::expm1(x) - x) / (x * x);
}

}  // namespace odeskin
