// SPDX-License-Identifier: MIT
#include "ode4_cardinal.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "scaled_ch_sh.hpp"

namespace odeskin {
namespace {

// |b| beyond 1e150 would overflow b^2; such boundary layers are far thinner than any u-sampling can
// see. |c| is bounded by accuracy, not overflow: the end slopes are differences of terms of size
// omega ~ |c|^(1/4), and swept over powers of ten (b from 0 to +-1e150, every regime, the four
// blend examples) the surfaces first miss their constraints by more than 1e-9 of the data at
// |c| = 1e16 on a double-root line (1.5e19 in regime C, 1e30 with b = 0). Up to 1e12 the worst
// miss is 4.6e-11, twenty times inside that check.
constexpr double kMaxB = 1e150;
constexpr double kMaxC = 1e12;

std::string num(double x) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", x);
  return text;
}

std::string params(double alpha, double beta, double gamma) {
  return "(alpha, beta, gamma) = (" + num(alpha) + ", " + num(beta) + ", " + num(gamma) + ")";
}

Status checkFinite(const char* name, double x) {
  if (std::isnan(x)) return invalidArgument(std::string("shape parameters: ") + name + " is NaN");
  if (!std::isfinite(x)) return invalidArgument(std::string("shape parameters: ") + name + " is infinite");
  return okStatus();
}

// Sign of beta^2 - 4 alpha gamma (the sign of D times alpha^2) with both products split into
// their rounded value and exact error, so the difference of two nearly equal squares keeps its
// sign. Falls back to D = b^2 - 4c (one fma) when a product overflows.
double discriminantSign(double alpha, double beta, double gamma, double b, double c) {
  const double p = alpha * gamma;
  const double q = beta * beta;
  if (std::isfinite(p) && std::isfinite(q)) {
    const double ep = std::fma(alpha, gamma, -p);
    const double eq = std::fma(beta, beta, -q);
    return (q - 4.0 * p) + (eq - 4.0 * ep);
  }
  return std::fma(b, b, -4.0 * c);
}

}  // namespace

const char* ode4RegimeName(Ode4Regime regime) {
  switch (regime) {
    case Ode4Regime::kTwoRealPairs: return "A: two real pairs +-p1, +-p2 (D > 0, c > 0, b < 0)";
    case Ode4Regime::kTwoImaginaryPairs: return "B: two imaginary pairs +-iq1, +-iq2 (D > 0, c > 0, b > 0)";
    case Ode4Regime::kRealAndImaginary: return "C: a real pair +-p and an imaginary pair +-iq (D > 0, c < 0)";
    case Ode4Regime::kZeroAndRealPair: return "D: double root 0 and a real pair +-p (c = 0, b < 0)";
    case Ode4Regime::kZeroAndImaginaryPair: return "E: double root 0 and an imaginary pair +-iq (c = 0, b > 0)";
    case Ode4Regime::kQuadrupleZero: return "F: quadruple root 0, cubic Hermite (b = c = 0)";
    case Ode4Regime::kRealDoublePair: return "G: real double pair +-p (D = 0, b < 0)";
    case Ode4Regime::kImaginaryDoublePair: return "H: imaginary double pair +-iq (D = 0, b > 0)";
    case Ode4Regime::kComplexQuadruple: return "I: complex quadruple +-a +- iw (D < 0)";
  }
  return "unknown";
}

Result<Ode4Regime> classifyOde4(double alpha, double beta, double gamma) {
  ODESKIN_TRY(checkFinite("alpha", alpha));
  ODESKIN_TRY(checkFinite("beta", beta));
  ODESKIN_TRY(checkFinite("gamma", gamma));
  if (alpha == 0.0) {
    if (beta == 0.0 && gamma == 0.0) {
      return degenerate("shape parameters: alpha = beta = gamma = 0: the equation carries no information");
    }
    return degenerate("shape parameters: alpha = 0: the ODE drops to second order and cannot meet the four position and "
                      "tangent constraints (MATH.md 2.8)");
  }
  const double b = beta / alpha;
  const double c = gamma / alpha;
  if (!(std::fabs(b) <= kMaxB)) {
    return invalidArgument("shape parameters: beta/alpha = " + num(b) + " is outside [-1e150, 1e150] " +
                           params(alpha, beta, gamma));
  }
  if (!(std::fabs(c) <= kMaxC)) {
    return invalidArgument("shape parameters: gamma/alpha = " + num(c) + " is outside [-1e12, 1e12] (beyond it the "
                           "solution misses its end conditions) " + params(alpha, beta, gamma));
  }
  if (c == 0.0) {
    if (b == 0.0) return Ode4Regime::kQuadrupleZero;
    return b < 0.0 ? Ode4Regime::kZeroAndRealPair : Ode4Regime::kZeroAndImaginaryPair;
  }
  const double d = discriminantSign(alpha, beta, gamma, b, c);
  if (d < 0.0) return Ode4Regime::kComplexQuadruple;
  if (d == 0.0) return b < 0.0 ? Ode4Regime::kRealDoublePair : Ode4Regime::kImaginaryDoublePair;
  if (c < 0.0) return Ode4Regime::kRealAndImaginary;
  return b < 0.0 ? Ode4Regime::kTwoRealPairs : Ode4Regime::kTwoImaginaryPairs;
}

Result<Ode4Cardinal> Ode4Cardinal::create(double alpha, double beta, double gamma) {
  ODESKIN_ASSIGN_OR_RETURN(const Ode4Regime regime, classifyOde4(alpha, beta, gamma));
  Ode4Cardinal out;
  out.alpha_ = alpha;
  out.beta_ = beta;
  out.gamma_ = gamma;
  out.regime_ = regime;
  out.b_ = beta / alpha;
  out.c_ = gamma / alpha;
  const double w = out.chooseBasis();
  const BlockRatios ratios = out.setUpBlocks(w);
  out.hadamard_ratio_ = ratios.smaller();
  // `!(ratio >= threshold)` also catches a NaN ratio from a zero column.
  if (!(ratios.even >= kOde4ResonanceThreshold) || !(ratios.odd >= kOde4ResonanceThreshold)) {
    const bool even = !(ratios.even >= kOde4ResonanceThreshold);
    char ratio_text[32];
    std::snprintf(ratio_text, sizeof ratio_text, "%.2e", even ? ratios.even : ratios.odd);
    return illPosed("shape parameters: " + params(alpha, beta, gamma) + " is resonant: the " +
                    (even ? "symmetric (even)" : "antisymmetric (odd)") +
                    " boundary-value problem has no unique solution (Hadamard ratio " + ratio_text +
                    " < 1e-10, MATH.md 2.7); move beta or gamma away from this value");
  }
  return out;
}

double Ode4Cardinal::chooseBasis() {
  const double b = b_;
  const double c = c_;
  // MATH.md 2.5-2.6: frequency scale, branch thresholds, and the slope-row scale W.
  const double omega = std::max(std::sqrt(std::fabs(b)), std::sqrt(std::sqrt(std::fabs(c))));
  const double w = std::max(1.0, omega);
  const double d = std::fma(b, b, -4.0 * c);  // b^2 - 4c rounded once
  if (omega <= 1.0) {
    basis_ = Ode4Basis::kSeries;
    // Y_k^(n)(0) from y'''' = -b y'' - c y: a_{n+4} = -b a_{n+2} - c a_n, a_j = delta_jk for j < 4.
    for (int k = 0; k < 4; ++k) {
      auto& a = series_[static_cast<std::size_t>(k)];
      a.fill(0.0);
      a[static_cast<std::size_t>(k)] = 1.0;
      for (std::size_t n = 0; n + 4 <= static_cast<std::size_t>(kSeriesTerms); ++n) a[n + 4] = -b * a[n + 2] - c * a[n];
    }
  } else if (d >= 0.25 * omega * omega * omega * omega) {
    useRealRoots(d);
  } else {
    basis_ = Ode4Basis::kPq;
    // X1 = (sqrt(c) - b/2)/2, X2 = -(sqrt(c) + b/2)/2 (c > 0 on this branch); the one that
    // cancels near D = 0 is rewritten as D over the sum that does not.
    const double sqrt_c = std::sqrt(c);
    if (b >= 0.0) {
      x2_ = -0.5 * (sqrt_c + 0.5 * b);
      x1_ = -d / (8.0 * (sqrt_c + 0.5 * b));
    } else {
      x1_ = 0.5 * (sqrt_c - 0.5 * b);
      x2_ = d / (8.0 * (sqrt_c - 0.5 * b));
    }
  }
  return w;
}

void Ode4Cardinal::useRealRoots(double d) {
  basis_ = Ode4Basis::kReal;
  // Stable quadratic formula: s1 is the root of larger magnitude (never 0 when D > 0), s2 = c / s1.
  const double sqrt_d = std::sqrt(d);
  x1_ = b_ >= 0.0 ? 0.5 * (-b_ - sqrt_d) : 0.5 * (-b_ + sqrt_d);
  x2_ = c_ / x1_;
}

Ode4Cardinal::BlockRatios Ode4Cardinal::invertBlocks(double w) {
  // 2x2 block inverses at t = +1/2 with slope rows divided by W (MATH.md 2.5). For a block basis
  // (f, g): V = (G' f - F' g)/Wr and Dd = (F g - G f)/Wr with Wr = F G' - G F'.
  auto invert = [w](const Pair& p, double& ratio) {
    const double fp = p.df / w;
    const double gp = p.dg / w;
    const double wr = p.f * gp - p.g * fp;
    ratio = std::fabs(wr) / (std::hypot(p.f, fp) * std::hypot(p.g, gp));
    BlockInverse inv;
    inv.v_f = gp / wr;
    inv.v_g = -fp / wr;
    inv.d_f = -p.g / (wr * w);
    inv.d_g = p.f / (wr * w);
    return inv;
  };
  BlockRatios ratios;
  even_ = invert(evenPair(0.5), ratios.even);
  odd_ = invert(oddPair(0.5), ratios.odd);
  return ratios;
}

Ode4Cardinal::BlockRatios Ode4Cardinal::setUpBlocks(double w) {
  const BlockRatios ratios = invertBlocks(w);
  if (basis_ != Ode4Basis::kPq || !(x2_ > 0.0)) return ratios;
  // Regime A (X2 = Q^2 > 0): the pq products are (cosh p1 t +- cosh p2 t) / 2 (over PQ for the
  // second) with p1 = P + Q, p2 = P - Q, so at the ends both are cosh p1 t up to a part e^{-Q}
  // smaller and the block ratio falls like e^{-Q}. The real basis scales each exponential on its
  // own; its ratio falls only like Q / W, as the roots merge at D = 0. Q^2 = D / (8 (sqrt(c) - b/2))
  // grows with |b| at a fixed D / omega^4, so no threshold on D suits every |b|: MATH.md 2.6's
  // D >= omega^4 / 4 left misses of 1.6e-5 (b = -3e4, c = 2e8) and, from b = -5e4, refused these
  // never-resonant parameters (MATH.md 2.7) as resonant. The better of the two is kept.
  Ode4Cardinal real = *this;
  real.useRealRoots(std::fma(b_, b_, -4.0 * c_));
  const BlockRatios real_ratios = real.invertBlocks(w);
  if (!(real_ratios.smaller() > ratios.smaller())) return ratios;
  *this = real;
  return real_ratios;
}

Ode4Cardinal::Pair Ode4Cardinal::seriesPair(int first, double t) const {
  // Y(t) = sum a_n t^n/n!, Y'(t) = sum a_{n+1} t^n/n! for Y_first and Y_{first+2}.
  const auto& a = series_[static_cast<std::size_t>(first)];
  const auto& b = series_[static_cast<std::size_t>(first) + 2];
  Pair out;
  double term = 1.0;  // t^n / n!
  for (std::size_t n = 0; n < static_cast<std::size_t>(kSeriesTerms); ++n) {
    out.f += a[n] * term;
    out.df += a[n + 1] * term;
    out.g += b[n] * term;
    out.dg += b[n + 1] * term;
    term *= t / static_cast<double>(n + 1);
  }
  return out;
}

Ode4Cardinal::Pair Ode4Cardinal::evenPair(double t) const {
  if (basis_ == Ode4Basis::kSeries) return seriesPair(0, t);
  const ScaledChSh a = scaledChSh(x1_, t);
  const ScaledChSh b = scaledChSh(x2_, t);
  if (basis_ == Ode4Basis::kReal) return {a.ch, x1_ * a.sh, b.ch, x2_ * b.sh};
  // {Ch(X1) Ch(X2), Sh(X1) Sh(X2)}, derivatives by the Leibniz rule.
  return {a.ch * b.ch, x1_ * a.sh * b.ch + x2_ * a.ch * b.sh, a.sh * b.sh, a.ch * b.sh + a.sh * b.ch};
}

Ode4Cardinal::Pair Ode4Cardinal::oddPair(double t) const {
  if (basis_ == Ode4Basis::kSeries) return seriesPair(1, t);
  const ScaledChSh a = scaledChSh(x1_, t);
  const ScaledChSh b = scaledChSh(x2_, t);
  if (basis_ == Ode4Basis::kReal) return {a.sh, a.ch, b.sh, b.ch};
  // {Sh(X1) Ch(X2), Ch(X1) Sh(X2)}.
  return {a.sh * b.ch, a.ch * b.ch + x2_ * a.sh * b.sh, a.ch * b.sh, x1_ * a.sh * b.sh + a.ch * b.ch};
}

CardinalSample Ode4Cardinal::at(double u) const {
  const double t = u - 0.5;
  const Pair e = evenPair(t);
  const Pair o = oddPair(t);
  // Block-cardinal functions: value (V) and slope (D) unit conditions at t = +1/2 only.
  const double ev = even_.v_f * e.f + even_.v_g * e.g;
  const double dev = even_.v_f * e.df + even_.v_g * e.dg;
  const double ed = even_.d_f * e.f + even_.d_g * e.g;
  const double ded = even_.d_f * e.df + even_.d_g * e.dg;
  const double ov = odd_.v_f * o.f + odd_.v_g * o.g;
  const double dov = odd_.v_f * o.df + odd_.v_g * o.dg;
  const double od = odd_.d_f * o.f + odd_.d_g * o.g;
  const double dod = odd_.d_f * o.df + odd_.d_g * o.dg;
  // MATH.md 2.5: the even part mirrors its end condition to u = 0, the odd part flips it.
  CardinalSample s;
  s.r = {0.5 * (ev - ov), 0.5 * (od - ed), 0.5 * (ev + ov), 0.5 * (od + ed)};
  s.dr = {0.5 * (dev - dov), 0.5 * (dod - ded), 0.5 * (dev + dov), 0.5 * (dod + ded)};
  return s;
}

}  // namespace odeskin
