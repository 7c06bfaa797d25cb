// SPDX-License-Identifier: MIT
// Time basis of one Fourier mode, MATH.md 5.2-5.5 (thesis Eqs 6.17-6.29 corrected, errata G2-G7).
// Second order: gamma = Q/Q(1), psi = H - H(1) gamma with Q = rho P (Q'' + 2 kappa Q' + k Q = t).
#include "time_basis.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "series_functions.hpp"

namespace odeskin {

namespace {

// Normalised second-order mode: kappa = eta/(2 rho), k = h/rho, x = kappa^2 - k (MATH.md 5.3).
struct Normalised {
  double kappa;
  double k;
  double x;
};

struct Impulse {
  double h;   // H(t): H(0) = 0, H'(0) = 1
  double dh;  // H'(t)
  double kk;  // K(t) = e^{-kappa t} (Ch + kappa Sh), K(0) = 1, K' = -k H
};

struct Forced {
  double q;   // Q(t)
  double dq;  // Q'(t)
};

// MATH.md 5.5 step 1: 60 Taylor terms converge to float64 precision while m |t| <= 2, because every
// characteristic root satisfies |r| <= (1 + sqrt 2) m, so the terms fall like 4.9^n/n!.
constexpr int kTaylorTerms = 60;
constexpr double kTaylorLimit = 2.0;
// MATH.md 5.5 step 3: roots real and separated enough that the root form does not cancel.
constexpr double kDampingDominance = 5.0;
// MATH.md 5.4: resonance when |Q(1)| < 1e-9 max_j |Q(j/16)|, i.e. |gamma| would exceed 1e9.
constexpr double kResonanceRatio = 1e-9;
constexpr int kResonanceGrid = 16;

// Roots -kappa +/- sqrt(x) of r^2 + 2 kappa r + k (x > 0). The one that would cancel is taken as
// k / (the other), MATH.md 5.5 step 3.
void realRoots(const Normalised& n, double* r_plus, double* r_minus) {
  const double mu = std::sqrt(n.x);
  if (n.kappa > 0.0) {
    *r_minus = -n.kappa - mu;
    *r_plus = n.k / *r_minus;
  } else {
    *r_plus = -n.kappa + mu;
    *r_minus = n.k / *r_plus;
  }
}

// H, H', K of MATH.md 5.3 (H = e^{-kappa t} Sh(X,t), H' = e^{-kappa t}(Ch - kappa Sh)).
Impulse impulse(const Normalised& n, double t) {
  if (n.x <= 0.0 || n.x * t * t <= 1.0) {
    // Oscillatory or nearly critical: Ch/Sh are bounded here and entire in X (MATH.md 1.3).
    const ChSh cs = chSh(n.x, t);
    const double decay = std::exp(-n.kappa * t);
    return {decay * cs.sh, decay * (cs.ch - n.kappa * cs.sh), decay * (cs.ch + n.kappa * cs.sh)};
  }
  // Real roots: H = (e^{r+ t} - e^{r- t})/(2 mu), H' = (r+ e^{r+ t} - r- e^{r- t})/(2 mu),
  // K = (r+ e^{r- t} - r- e^{r+ t})/(2 mu). The dominant exponential is factored out so that
  // e^{-kappa t} sinh(mu t) never forms inf * 0 (e.g. kappa = 1000, mu ~ 1000 at t = 1).
  double r_plus = 0.0;
  double r_minus = 0.0;
  realRoots(n, &r_plus, &r_minus);
  const double two_mu = 2.0 * std::sqrt(n.x);
  const bool forward = t >= 0.0;
  const double lead = std::exp((forward ? r_plus : r_minus) * t);
  const double ratio = std::exp((forward ? r_minus - r_plus : r_plus - r_minus) * t);  // <= e^{-2}
  const double e_plus = forward ? 1.0 : ratio;
  const double e_minus = forward ? ratio : 1.0;
  return {lead * (e_plus - e_minus) / two_mu, lead * (r_plus * e_plus - r_minus * e_minus) / two_mu,
          lead * (r_plus * e_minus - r_minus * e_plus) / two_mu};
}

// Q, Q' by the scaled Taylor recursion of MATH.md 5.5 step 1 (q_n itself would overflow for huge
// kappa or k): b_3 = t^3/6, b_{j} = -2 kappa t b_{j-1}/j - k t^2 b_{j-2}/((j-1) j).
Forced forcedTaylor(const Normalised& n, double t) {
  if (t == 0.0) return {0.0, 0.0};
  double b_prev = 0.0;
  double b_cur = t * t * t / 6.0;
  double q = b_cur;
  double tq = 3.0 * b_cur;  // sum j b_j = t Q'
  for (int j = 4; j < kTaylorTerms; ++j) {
    const double jd = static_cast<double>(j);
    const double b_next = -2.0 * n.kappa * t * b_cur / jd - n.k * t * t * b_prev / ((jd - 1.0) * jd);
    q += b_next;
    tq += jd * b_next;
    b_prev = b_cur;
    b_cur = b_next;
  }
  return {q, tq / t};
}

// Q(t), Q'(t) with the branch choice of MATH.md 5.5.
Forced forced(const Normalised& n, double t) {
  const double m = std::max(std::fabs(n.kappa), std::sqrt(std::fabs(n.k)));
  if (m * std::fabs(t) <= kTaylorLimit) return forcedTaylor(n, t);
  if (!(n.x > 0.0 && n.kappa * n.kappa > kDampingDominance * std::fabs(n.k))) {
    // Spring-dominated (k != 0 here, |k| t^2 >= 0.8): Q' = (1 - K)/k, Q = (t - H - 2 kappa Q')/k.
    const Impulse imp = impulse(n, t);
    const double dq = (1.0 - imp.kk) / n.k;
    return {(t - imp.h - 2.0 * n.kappa * dq) / n.k, dq};
  }
  // Damping-dominated: Q = t^2 (phi2(r1 t) - phi2(r2 t))/(r1 - r2),
  //                    Q' = t (phi1(r1 t) - phi1(r2 t))/(r1 - r2).
  double r_plus = 0.0;
  double r_minus = 0.0;
  realRoots(n, &r_plus, &r_minus);
  const double gap = r_plus - r_minus;
  return {t * t * (phi2(r_plus * t) - phi2(r_minus * t)) / gap,
          t * (phi1(r_plus * t) - phi1(r_minus * t)) / gap};
}

std::string modeLabel(double rho, double eta, double h, int mode) {
  char buffer[160];
  std::snprintf(buffer, sizeof(buffer), "mode %d (rho=%.5g, eta=%.5g, h=%.5g)", mode, rho, eta, h);
  return buffer;
}

Status checkFinite(double value, const char* name, int mode) {
  if (std::isfinite(value)) return okStatus();
  return invalidArgument("mode " + std::to_string(mode) + ": " + name + " is " +
                         (std::isnan(value) ? "NaN" : "infinite"));
}

}  // namespace

Result<ModeTimeBasis> ModeTimeBasis::create(double rho, double eta, double h, int mode) {
  ODESKIN_TRY(checkFinite(rho, "rho", mode));
  ODESKIN_TRY(checkFinite(eta, "eta", mode));
  ODESKIN_TRY(checkFinite(h, "h", mode));
  const std::string label = modeLabel(rho, eta, h, mode);
  ModeTimeBasis basis;
  basis.rho_ = rho;
  basis.eta_ = eta;
  basis.h_ = h;

  if (rho == 0.0 && eta == 0.0) {
    // MATH.md 5.3: 0 = t e carries no information; h a = t e gives gamma = t.
    if (h == 0.0) return degenerate(label + ": rho = eta = h = 0, the mode equation reads 0 = t e");
    basis.kind_ = ModeKind::kStatic;
    return basis;
  }

  if (rho == 0.0) {
    // First order (MATH.md 5.3): gamma = t^2 phi2(c t)/phi2(c), c = -h/eta; phi2 > 0, never resonant.
    basis.kind_ = ModeKind::kFirstOrder;
    basis.c_ = -h / eta;
    if (!std::isfinite(basis.c_))
      return invalidArgument(label + ": h/eta overflows float64 (eta too small for this h)");
    // For c > 1 numerator and normaliser are both scaled by e^{-c} so e^c cannot overflow.
    basis.norm_ = basis.c_ > 1.0 ? 1.0 - std::exp(-basis.c_) * (1.0 + basis.c_) : phi2(basis.c_);
    return basis;
  }

  basis.kind_ = ModeKind::kSecondOrder;
  basis.kappa_ = eta / (2.0 * rho);
  basis.k_ = h / rho;
  basis.x_ = basis.kappa_ * basis.kappa_ - basis.k_;
  if (!std::isfinite(basis.kappa_) || !std::isfinite(basis.k_) || !std::isfinite(basis.x_))
    return invalidArgument(label + ": eta/rho or h/rho overflows float64 (rho too small; use rho = 0)");
  const Normalised n{basis.kappa_, basis.k_, basis.x_};

  const Forced at_one = forced(n, 1.0);
  const Impulse impulse_one = impulse(n, 1.0);
  if (!std::isfinite(at_one.q) || !std::isfinite(impulse_one.h))
    return illPosed(label + ": exponential growth overflows float64 on [0, 1]");
  double q_max = 0.0;
  for (int j = 1; j <= kResonanceGrid; ++j)
    q_max = std::max(q_max, std::fabs(forced(n, static_cast<double>(j) / kResonanceGrid).q));
  if (at_one.q == 0.0 || std::fabs(at_one.q) < kResonanceRatio * q_max)
    return illPosed(label + ": resonant: P(1) = 0, the time basis would exceed 1e9");
  basis.q1_ = at_one.q;
  basis.h1_ = impulse_one.h;
  return basis;
}

Result<ModeTimeBasis> ModeTimeBasis::create(const Material& material, int n) {
  if (n < 0) return invalidArgument("mode " + std::to_string(n) + ": mode index must be >= 0");
  ODESKIN_TRY(checkFinite(material.zeta, "zeta", n));
  ODESKIN_TRY(checkFinite(material.xi, "xi", n));
  return create(material.rho, material.eta, modeStiffness(material, n), n);
}

namespace {

// For finite t the formulas produce NaN only as inf - inf, inf/inf or 0 * inf, i.e. once the true
// value has left the float64 range (|t| far outside [0, 1] for a growing or strongly damped mode,
// where even its sign is lost). Report those as +inf so that an isfinite check catches them.
TimeBasisSample overflowAsInfinity(TimeBasisSample s) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  for (double* v : {&s.gamma, &s.dgamma, &s.psi, &s.dpsi})
    if (std::isnan(*v)) *v = kInf;
  return s;
}

}  // namespace

TimeBasisSample ModeTimeBasis::at(double t) const {
  switch (kind_) {
    case ModeKind::kSecondOrder: {
      const TimeBasisSample s = atSecondOrder(t);
      return std::isnan(t) ? s : overflowAsInfinity(s);
    }
    case ModeKind::kFirstOrder: {
      const TimeBasisSample s = atFirstOrder(t);
      return std::isnan(t) ? s : overflowAsInfinity(s);
    }
    case ModeKind::kStatic: break;
  }
  // h a = t e with a(1) = d (MATH.md 5.3): gamma = t, the rate is not an input.
  return {t, 1.0, 0.0, 0.0};
}

TimeBasisSample ModeTimeBasis::atSecondOrder(double t) const {
  const Normalised n{kappa_, k_, x_};
  const Forced f = forced(n, t);
  const Impulse imp = impulse(n, t);
  const double gamma = f.q / q1_;
  const double dgamma = f.dq / q1_;
  // MATH.md 5.2: psi = H - H(1) gamma, so psi(1) = 0 and psi'(0) = H'(0) = 1.
  return {gamma, dgamma, imp.h - h1_ * gamma, imp.dh - h1_ * dgamma};
}

TimeBasisSample ModeTimeBasis::atFirstOrder(double t) const {
  const double ct = c_ * t;
  if (c_ <= 1.0) {
    // gamma = t^2 phi2(c t)/phi2(c), gamma' = t phi1(c t)/phi2(c) (MATH.md 5.3).
    return {t * t * phi2(ct) / norm_, t * phi1(ct) / norm_, 0.0, 0.0};
  }
  // c > 1 (growth): gamma = (e^{ct} - 1 - ct)/(e^c - 1 - c), everything multiplied by e^{-c}.
  const double scale = std::exp(-c_);
  double num = 0.0;
  double dnum = 0.0;
  if (ct >= 1.0) {
    num = std::exp(c_ * (t - 1.0)) - scale * (1.0 + ct);
    dnum = c_ * (std::exp(c_ * (t - 1.0)) - scale);
  } else {
    // e^{ct} - 1 - ct cancels for small c t: use its series form (ct)^2 phi2(ct).
    num = scale * ct * ct * phi2(ct);
    dnum = c_ * scale * std::expm1(ct);
  }
  return {num / norm_, dnum / norm_, 0.0, 0.0};
}

double ModeTimeBasis::impulseResponseAtOne() const {
  return kind_ == ModeKind::kSecondOrder ? std::fabs(h1_) : 0.0;
}

bool ModeTimeBasis::negativeDamping() const {
  // Sign of eta/rho without dividing; a first-order mode has only eta to look at.
  return rho_ != 0.0 ? (eta_ < 0.0) != (rho_ < 0.0) && eta_ != 0.0 : eta_ < 0.0;
}

bool ModeTimeBasis::growthMode() const {
  switch (kind_) {
    case ModeKind::kSecondOrder: return k_ < 0.0;
    case ModeKind::kFirstOrder: return c_ > 0.0;
    case ModeKind::kStatic: break;
  }
  return false;
}

}  // namespace odeskin
