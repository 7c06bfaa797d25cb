// SPDX-License-Identifier: MIT
#include "ode6_cardinal.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <sstream>

#include <Eigen/Dense>

#include "../core/number_text.hpp"

namespace odeskin {
namespace {

// sinh(y)/y, from its series where the quotient would lose digits.
double sinhc(double y) {
  if (std::abs(y) < 1e-3) {
    const double y2 = y * y;
    return 1.0 + y2 / 6.0 + y2 * y2 / 120.0;
  }
  return std::sinh(y) / y;
}

// sin(z)/z likewise.
double sinc(double z) {
  if (std::abs(z) < 1e-3) {
    const double z2 = z * z;
    return 1.0 - z2 / 6.0 + z2 * z2 / 120.0;
  }
  return std::sin(z) / z;
}

// phis(w) = sum_k w^k / (2k+3)! for |w| < 1 (MATH.md 1.4): St(X, t) = t^3 phis(X t^2).
double phis(double w) {
  double term = 1.0 / 6.0;
  double sum = term;
  for (int k = 1; k < 16; ++k) {
    term *= w / ((2.0 * k + 2.0) * (2.0 * k + 3.0));
    sum += term;
    if (std::abs(term) < 1e-18 * std::abs(sum)) break;
  }
  return sum;
}

// Ch, Sh, Ct, St of MATH.md 1.3 at (X, t), |t| <= 1/2, all divided by N(X) = cosh(sqrt(X)/2) for
// X > 0 (N = 1 otherwise) so that nothing overflows however large X is (MATH.md 1.4).
struct Scaled {
  double x = 0.0;
  double ch = 1.0;
  double sh = 0.0;
  double ct = 0.0;
  double st = 0.0;
};

Scaled scaledFunctions(double x, double t) {
  Scaled s;
  s.x = x;
  const double t2 = t * t;
  if (x > 0.0) {
    const double p = std::sqrt(x);
    const double a = std::abs(t);
    const double den = 1.0 + std::exp(-p);
    const double inv_n = 2.0 * std::exp(-0.5 * p) / den;
    const double grow = std::exp(p * (a - 0.5));
    s.ch = grow * (1.0 + std::exp(-2.0 * p * a)) / den;
    if (p * a < 1e-3) {
      s.sh = t * sinhc(p * a) * inv_n;
    } else {
      s.sh = std::copysign(grow * -std::expm1(-2.0 * p * a) / (den * p), t);
    }
    if (x * t2 >= 1.0) {
      s.ct = (s.ch - inv_n) / x;
      s.st = (s.sh - t * inv_n) / x;
    } else {
      const double h = sinhc(0.5 * p * a);
      s.ct = 0.5 * t2 * h * h * inv_n;
      s.st = t * t2 * phis(x * t2) * inv_n;
    }
  } else if (x < 0.0) {
    const double q = std::sqrt(-x);
    s.ch = std::cos(q * t);
    s.sh = t * sinc(q * t);
    if (-x * t2 >= 1.0) {
      s.ct = (s.ch - 1.0) / x;
      s.st = (s.sh - t) / x;
    } else {
      const double h = sinc(0.5 * q * t);
      s.ct = 0.5 * t2 * h * h;
      s.st = t * t2 * phis(x * t2);
    }
  } else {
    s.sh = t;
    s.ct = 0.5 * t2;
    s.st = t * t2 / 6.0;
  }
  return s;
}

double power(double x, int k) {
  double r = 1.0;
  for (int i = 0; i < k; ++i) r *= x;
  return r;
}

// m-th t-derivatives, from Ch' = X Sh, Sh' = Ch, Ct' = Sh, St' = Ct.
double chD(const Scaled& s, int m) { return m % 2 == 0 ? power(s.x, m / 2) * s.ch : power(s.x, (m + 1) / 2) * s.sh; }
double shD(const Scaled& s, int m) { return m % 2 == 0 ? power(s.x, m / 2) * s.sh : power(s.x, (m - 1) / 2) * s.ch; }
double ctD(const Scaled& s, int m) { return m == 0 ? s.ct : m == 1 ? s.sh : chD(s, m - 2); }
double stD(const Scaled& s, int m) { return m == 0 ? s.st : m == 1 ? s.ct : m == 2 ? s.sh : chD(s, m - 3); }

double binomial(int n, int k) {
  double r = 1.0;
  for (int i = 1; i <= k; ++i) r = r * (n - k + i) / i;
  return r;
}

// (f g)^(m) by the Leibniz rule.
template <typename F, typename G>
double productD(const F& f, const G& g, int m) {
  double sum = 0.0;
  for (int i = 0; i <= m; ++i) sum += binomial(m, i) * f(i) * g(m - i);
  return sum;
}

struct BlockValues {
  std::array<double, 3> even{};
  std::array<double, 3> odd{};
};

using SeriesTable = std::array<std::array<double, kOde6SeriesTerms + kOde6MaxDerivative + 1>, 4>;

// Y_k^(m)(t) = sum_n a_(n+m) t^n / n!.
double seriesD(const SeriesTable& series, int k, double t, int m) {
  if (k == 0) return m == 0 ? 1.0 : 0.0;
  if (k == 1) return m == 0 ? t : m == 1 ? 1.0 : 0.0;
  const auto& a = series[static_cast<std::size_t>(k - 2)];
  double sum = 0.0;
  double power_over_factorial = 1.0;
  for (int n = 0; n < kOde6SeriesTerms; ++n) {
    sum += a[static_cast<std::size_t>(n) + static_cast<std::size_t>(m)] * power_over_factorial;
    power_over_factorial *= t / (n + 1);
  }
  return sum;
}

// The basis functions of both blocks (MATH.md 3.4), m-th derivative at t. s1 and s2 are the
// scaled primitives at (x1, t) and (x2, t) (unused by the series branch).
BlockValues basisValues(const Ode6Basis& basis, const SeriesTable& series, const Scaled& s1, const Scaled& s2, double t,
                        int m) {
  BlockValues v;
  v.even[0] = m == 0 ? 1.0 : 0.0;
  v.odd[0] = m == 0 ? t : m == 1 ? 1.0 : 0.0;
  switch (basis.branch) {
    case Ode6Branch::kSeries:
      v.even[0] = seriesD(series, 0, t, m);
      v.even[1] = seriesD(series, 2, t, m);
      v.even[2] = seriesD(series, 4, t, m);
      v.odd[0] = seriesD(series, 1, t, m);
      v.odd[1] = seriesD(series, 3, t, m);
      v.odd[2] = seriesD(series, 5, t, m);
      break;
    case Ode6Branch::kReal:
      v.even[1] = ctD(s1, m);
      v.even[2] = ctD(s2, m);
      v.odd[1] = stD(s1, m);
      v.odd[2] = stD(s2, m);
      break;
    case Ode6Branch::kPq: {
      auto ch1 = [&](int i) { return chD(s1, i); };
      auto sh1 = [&](int i) { return shD(s1, i); };
      auto ch2 = [&](int i) { return chD(s2, i); };
      auto sh2 = [&](int i) { return shD(s2, i); };
      v.even[1] = productD(ch1, ch2, m);
      v.even[2] = productD(sh1, sh2, m);
      v.odd[1] = productD(sh1, ch2, m);
      v.odd[2] = productD(ch1, sh2, m);
      break;
    }
  }
  return v;
}

// Taylor coefficients of Y_2 .. Y_5: a_(n+6) = -b a_(n+4) - c a_(n+2) (the ODE divided by rho).
SeriesTable seriesCoefficients(double b, double c) {
  SeriesTable table{};
  for (int k = 2; k < 6; ++k) {
    auto& a = table[static_cast<std::size_t>(k - 2)];
    a[static_cast<std::size_t>(k)] = 1.0;
    for (std::size_t n = 0; n + 6 < a.size(); ++n) a[n + 6] = -b * a[n + 4] - c * a[n + 2];
  }
  return table;
}

std::string shapeText(const Ode6Shape& s) {
  std::ostringstream out;
  out.precision(17);
  out << "(rho, eta, lambda) = (" << s.rho << ", " << s.eta << ", " << s.lambda << ")";
  return out.str();
}

}  // namespace

const char* ode6RegimeName(Ode6Regime regime) {
  switch (regime) {
    case Ode6Regime::kA: return "A (D > 0, c > 0, b < 0: two real pairs)";
    case Ode6Regime::kB: return "B (D > 0, c > 0, b > 0: two imaginary pairs)";
    case Ode6Regime::kC: return "C (D > 0, c < 0: a real and an imaginary pair)";
    case Ode6Regime::kD: return "D (c = 0, b < 0: r = 0 quadruple and a real pair)";
    case Ode6Regime::kE: return "E (c = 0, b > 0: r = 0 quadruple and an imaginary pair)";
    case Ode6Regime::kF: return "F (b = c = 0: quintic Hermite)";
    case Ode6Regime::kG: return "G (D = 0, b < 0: a double real pair)";
    case Ode6Regime::kH: return "H (D = 0, b > 0: a double imaginary pair)";
    case Ode6Regime::kI: return "I (D < 0: a complex quadruple)";
  }
  return "?";
}

Ode6Regime classifyOde6(double b, double c) {
  if (c == 0.0) return b == 0.0 ? Ode6Regime::kF : b < 0.0 ? Ode6Regime::kD : Ode6Regime::kE;
  const double d = b * b - 4.0 * c;
  if (d == 0.0) return b < 0.0 ? Ode6Regime::kG : Ode6Regime::kH;
  if (d < 0.0) return Ode6Regime::kI;
  if (c < 0.0) return Ode6Regime::kC;
  return b < 0.0 ? Ode6Regime::kA : Ode6Regime::kB;
}

Result<Ode6Cardinal> Ode6Cardinal::create(const Ode6Shape& shape) {
  if (!std::isfinite(shape.rho) || !std::isfinite(shape.eta) || !std::isfinite(shape.lambda)) {
    return invalidArgument("ode6: shape parameters must be finite numbers, got " + shapeText(shape));
  }
  if (shape.rho == 0.0) {
    return degenerate("ode6: rho = 0 leaves a fourth-order ODE that cannot meet six boundary conditions, " +
                      shapeText(shape));
  }
  Ode6Cardinal g;
  g.shape_ = shape;
  Ode6Basis& basis = g.basis_;
  basis.b = shape.eta / shape.rho;
  basis.c = shape.lambda / shape.rho;
  const double b = basis.b;
  const double c = basis.c;
  if (!std::isfinite(b) || !std::isfinite(c)) {
    return outOfRange("ode6: eta/rho or lambda/rho overflows, " + shapeText(shape));
  }
  const double omega4 = std::max(b * b, std::abs(c));  // omega^4
  const double omega = std::max(std::sqrt(std::abs(b)), std::sqrt(std::sqrt(std::abs(c))));
  if (!(omega <= kOde6MaxFrequency)) {
    return outOfRange("ode6: frequency scale max(sqrt|eta/rho|, |lambda/rho|^(1/4)) = " + messageNumber(omega) +
                      " exceeds " + messageNumber(kOde6MaxFrequency) + ", " + shapeText(shape));
  }
  g.regime_ = classifyOde6(b, c);
  basis.w = std::max(1.0, omega);
  const double d = b * b - 4.0 * c;
  if (omega <= 3.0) {
    basis.branch = Ode6Branch::kSeries;
    g.series_ = seriesCoefficients(b, c);
  } else if (d >= omega4 / 4.0) {
    // Stable quadratic formula: s1 is the root of larger magnitude, s2 = c / s1 never cancels.
    basis.branch = Ode6Branch::kReal;
    const double root_d = std::sqrt(d);
    basis.x1 = b >= 0.0 ? 0.5 * (-b - root_d) : 0.5 * (-b + root_d);
    basis.x2 = c / basis.x1;
  } else {
    basis.branch = Ode6Branch::kPq;  // here c > 0 (MATH.md 2.6)
    const double root_c = std::sqrt(c);
    basis.x1 = 0.5 * (root_c - 0.5 * b);
    basis.x2 = -0.5 * (root_c + 0.5 * b);
  }

  // Rows (value, slope / W, curvature / W^2) at t = 1/2, one column per basis function.
  const Scaled s1 = scaledFunctions(basis.x1, 0.5);
  const Scaled s2 = scaledFunctions(basis.x2, 0.5);
  Eigen::Matrix3d even;
  Eigen::Matrix3d odd;
  for (int j = 0; j < 3; ++j) {
    const BlockValues v = basisValues(basis, g.series_, s1, s2, 0.5, j);
    const double scale = 1.0 / power(basis.w, j);
    for (int i = 0; i < 3; ++i) {
      even(j, i) = v.even[static_cast<std::size_t>(i)] * scale;
      odd(j, i) = v.odd[static_cast<std::size_t>(i)] * scale;
    }
  }
  auto hadamard = [](const Eigen::Matrix3d& m) {
    const double norms = m.col(0).norm() * m.col(1).norm() * m.col(2).norm();
    return norms > 0.0 ? std::abs(m.determinant()) / norms : 0.0;
  };
  g.hadamard_ratio_ = std::min(hadamard(even), hadamard(odd));
  if (!(g.hadamard_ratio_ >= kOde6ResonanceRatio)) {
    std::ostringstream out;
    out << "ode6: resonant shape parameters " << shapeText(shape) << ": the boundary-value problem has no unique "
        << "solution (Hadamard ratio " << g.hadamard_ratio_ << " < " << kOde6ResonanceRatio << ", MATH.md 3.5)";
    return illPosed(out.str());
  }
  // Inverted with unit columns, which the Hadamard test has just shown to be well conditioned.
  // FullPivLU's inverse drops what falls below its rank threshold (3 eps of the largest pivot), and
  // the real branch's St(s1) column, of entries near p^-3, went that way from p ~ 1.5e5: the
  // functions then missed their curvature conditions by 50% with no error.
  const auto inverse = [](const Eigen::Matrix3d& m) {
    const Eigen::Vector3d norms(m.col(0).norm(), m.col(1).norm(), m.col(2).norm());
    const Eigen::Matrix3d unit = m * norms.cwiseInverse().asDiagonal();
    return Eigen::Matrix3d(norms.cwiseInverse().asDiagonal() * unit.inverse());
  };
  const Eigen::Vector3d row_scale(1.0, 1.0 / basis.w, 1.0 / (basis.w * basis.w));
  const Eigen::Matrix3d even_inverse = inverse(even) * row_scale.asDiagonal();
  const Eigen::Matrix3d odd_inverse = inverse(odd) * row_scale.asDiagonal();
  for (std::size_t l = 0; l < 3; ++l) {
    for (std::size_t i = 0; i < 3; ++i) {
      basis.even[l][i] = even_inverse(static_cast<Eigen::Index>(l), static_cast<Eigen::Index>(i));
      basis.odd[l][i] = odd_inverse(static_cast<Eigen::Index>(l), static_cast<Eigen::Index>(i));
    }
  }
  return g;
}

void Ode6Cardinal::evaluate(double u, std::span<Ode6Values> out) const {
  assert(out.size() <= kOde6MaxDerivative + 1);
  const double t = u - 0.5;
  const Scaled s1 = scaledFunctions(basis_.x1, t);
  const Scaled s2 = scaledFunctions(basis_.x2, t);
  for (std::size_t m = 0; m < out.size(); ++m) {
    const BlockValues v = basisValues(basis_, series_, s1, s2, t, static_cast<int>(m));
    std::array<double, 3> e{};
    std::array<double, 3> o{};
    for (std::size_t i = 0; i < 3; ++i) {
      for (std::size_t l = 0; l < 3; ++l) {
        e[i] += v.even[l] * basis_.even[l][i];
        o[i] += v.odd[l] * basis_.odd[l][i];
      }
    }
    // MATH.md 3.3: g1 = (E0 - O0)/2, g2 = (O1 - E1)/2, g3 = (E2 - O2)/2, g4..g6 = (E_i + O_i)/2.
    out[m] = {0.5 * (e[0] - o[0]), 0.5 * (o[1] - e[1]), 0.5 * (e[2] - o[2]),
              0.5 * (e[0] + o[0]), 0.5 * (e[1] + o[1]), 0.5 * (e[2] + o[2])};
  }
}

Ode6Values Ode6Cardinal::evaluate(double u, int order) const {
  assert(order >= 0 && order <= kOde6MaxDerivative);
  std::array<Ode6Values, kOde6MaxDerivative + 1> all{};
  evaluate(u, std::span<Ode6Values>(all.data(), static_cast<std::size_t>(order) + 1));
  return all[static_cast<std::size_t>(order)];
}

}  // namespace odeskin
