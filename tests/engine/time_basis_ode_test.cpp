// SPDX-License-Identifier: MIT
// Property tests of the time basis that do not use the golden vectors: the closed forms of MATH.md
// 5.3/5.5 against a classical RK4 integration of the initial-value problems that define them
// (MATH.md 5.2), and the defining ODE and boundary conditions checked on a(t) = gamma d + psi rate.
#include "engine/offline/time_basis.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

namespace odeskin {
namespace {

struct Params {
  double rho, eta, h;
  const char* note;
};

// Covers every branch of MATH.md 5.5 (Taylor, spring-dominated, damping-dominated) and regime of 5.3.
const std::vector<Params> kSecondOrder = {
    {1.0, 0.5, 100.0, "underdamped"},
    {1.0, 2.0, 1.0, "critically damped"},
    {1.0, 2.0, 1.0 + 1e-9, "just underdamped"},
    {1.0, 10.0, 1.0, "overdamped"},
    {1.0, 200.0, 3.0, "heavily overdamped"},
    {2.0, 1.0, -84.0, "h < 0 growth"},
    {1.0, 0.0, -400.0, "h < 0, eta = 0, growth e^20"},
    {1.0, 200.0, -1.0, "h < 0 heavily damped"},
    {3.0, 3.0, 0.0, "h = 0 with damping"},
    {1.0, 0.0, 0.0, "h = 0, eta = 0"},
    {1.0, 0.0, 50.0, "eta = 0"},
    {1.0, 0.1, 2500.0, "stiff-ish, omega = 50"},
    {0.5, 0.02, 1250.0, "stiff-ish, rho = 0.5"},
    {1.0, -2.0, 50.0, "negative damping"},
    {1.0, -10.0, 30.0, "negative damping, near resonance"},
    {1050.0, 0.619, 1.0e4, "skin material"},
};

const std::vector<Params> kFirstOrder = {
    {0.0, 2.0, 5.0, "decay"},
    {0.0, 2.0, 0.0, "h = 0"},
    {0.0, 2.0, -5.0, "growth"},
    {0.0, 0.01, 1.0, "fast decay"},
    {0.0, 0.1, -3.0, "growth e^30"},
    {0.0, -1.0, 2.0, "negative eta"},
};

// RK4 over [0, 1]: 20000 steps keep |lambda| dt <= 0.01 for every set above (largest root ~200), so
// the global error is ~ (|lambda| dt)^4 ~ 1e-8 relative at worst and ~1e-11 typically, well below
// the 1e-7 tolerance, while any wrong term in a closed form changes gamma by O(1e-3) or more.
constexpr int kSteps = 20000;
constexpr int kSampleEvery = 500;  // compare at t = 0, 0.025, ..., 1
constexpr double kRelTol = 1e-7;

// y = (H, H', P, P'): rho H'' + eta H' + h H = 0, rho P'' + eta P' + h P = t (MATH.md 5.2).
using State2 = std::array<double, 4>;

State2 derivative2(const Params& p, double t, const State2& y) {
  return {y[1], -(p.eta * y[1] + p.h * y[0]) / p.rho, y[3], (t - p.eta * y[3] - p.h * y[2]) / p.rho};
}

template <typename State, typename F>
std::vector<State> integrateRk4(const State& y0, F f) {
  std::vector<State> samples{y0};
  State y = y0;
  const double dt = 1.0 / kSteps;
  auto axpy = [](const State& a, double s, const State& b) {
    State r{};
    for (size_t i = 0; i < a.size(); ++i) r[i] = a[i] + s * b[i];
    return r;
  };
  for (int i = 0; i < kSteps; ++i) {
    const double t = i * dt;
    const State k1 = f(t, y);
    const State k2 = f(t + 0.5 * dt, axpy(y, 0.5 * dt, k1));
    const State k3 = f(t + 0.5 * dt, axpy(y, 0.5 * dt, k2));
    const State k4 = f(t + dt, axpy(y, dt, k3));
    for (size_t j = 0; j < y.size(); ++j) y[j] += dt / 6.0 * (k1[j] + 2.0 * k2[j] + 2.0 * k3[j] + k4[j]);
    if ((i + 1) % kSampleEvery == 0) samples.push_back(y);
  }
  return samples;
}

void expectClose(double value, double ref, double tol, const Params& p, double t, const char* what) {
  EXPECT_LE(std::fabs(value - ref), tol * (1.0 + std::fabs(ref)))
      << p.note << " (rho=" << p.rho << ", eta=" << p.eta << ", h=" << p.h << "), t=" << t << ", "
      << what << ": closed form " << value << ", RK4 " << ref;
}

TEST(TimeBasisOde, SecondOrderMatchesRk4) {
  for (const Params& p : kSecondOrder) {
    const Result<ModeTimeBasis> basis = ModeTimeBasis::create(p.rho, p.eta, p.h);
    ASSERT_TRUE(basis.ok()) << p.note << ": " << basis.status().toString();
    const std::vector<State2> ys =
        integrateRk4(State2{0.0, 1.0, 0.0, 0.0},
                     [&](double t, const State2& y) { return derivative2(p, t, y); });
    const double p1 = ys.back()[2];
    const double h1 = ys.back()[0];
    EXPECT_LE(std::fabs(basis->impulseResponseAtOne() - std::fabs(h1)), kRelTol * (1.0 + std::fabs(h1)))
        << p.note;
    // psi = H - H(1) gamma amplifies the error of gamma by |H(1)| (MATH.md 5.5, conditioning of psi).
    const double psi_tol = kRelTol * (1.0 + std::fabs(h1));
    for (size_t i = 0; i < ys.size(); ++i) {
      const double t = static_cast<double>(i) / static_cast<double>(ys.size() - 1);
      const double gamma = ys[i][2] / p1;
      const double dgamma = ys[i][3] / p1;
      const TimeBasisSample s = basis->at(t);
      expectClose(s.gamma, gamma, kRelTol, p, t, "gamma");
      expectClose(s.dgamma, dgamma, kRelTol, p, t, "dgamma");
      expectClose(s.psi, ys[i][0] - h1 * gamma, psi_tol, p, t, "psi");
      expectClose(s.dpsi, ys[i][1] - h1 * dgamma, psi_tol, p, t, "dpsi");
    }
  }
}

TEST(TimeBasisOde, FirstOrderMatchesRk4) {
  for (const Params& p : kFirstOrder) {
    const Result<ModeTimeBasis> basis = ModeTimeBasis::create(p.rho, p.eta, p.h);
    ASSERT_TRUE(basis.ok()) << p.note << ": " << basis.status().toString();
    ASSERT_EQ(basis->kind(), ModeKind::kFirstOrder);
    // eta P' + h P = t, P(0) = 0 (MATH.md 5.3, first order).
    using State1 = std::array<double, 1>;
    const std::vector<State1> ys = integrateRk4(
        State1{0.0}, [&](double t, const State1& y) { return State1{(t - p.h * y[0]) / p.eta}; });
    const double p1 = ys.back()[0];
    for (size_t i = 0; i < ys.size(); ++i) {
      const double t = static_cast<double>(i) / static_cast<double>(ys.size() - 1);
      const TimeBasisSample s = basis->at(t);
      expectClose(s.gamma, ys[i][0] / p1, kRelTol, p, t, "gamma");
      expectClose(s.dgamma, (t - p.h * ys[i][0]) / (p.eta * p1), kRelTol, p, t, "dgamma");
      EXPECT_EQ(s.psi, 0.0);
      EXPECT_EQ(s.dpsi, 0.0);
    }
  }
}

// d/dt of a smooth f by the 4th-order central difference; its error is ~ delta^4 f^(5)/30.
template <typename F>
double derivative(F f, double t, double delta) {
  return (-f(t + 2 * delta) + 8 * f(t + delta) - 8 * f(t - delta) + f(t - 2 * delta)) / (12 * delta);
}

// a = gamma d + psi rate must satisfy a(0) = 0, a'(0) = rate, a(1) = d, and rho a'' + eta a' + h a
// must equal t e for one constant e: the residual divided by t is the same at every t.
TEST(TimeBasisOde, AssembledCoefficientSolvesTheModeProblem) {
  constexpr double kD = 0.7;
  constexpr double kRate = -1.3;
  constexpr double kDelta = 1e-3;
  std::vector<Params> all = kSecondOrder;
  all.insert(all.end(), kFirstOrder.begin(), kFirstOrder.end());
  for (const Params& p : all) {
    const Result<ModeTimeBasis> basis = ModeTimeBasis::create(p.rho, p.eta, p.h);
    ASSERT_TRUE(basis.ok()) << p.note;
    const double rate = basis->rateIgnored() ? 0.0 : kRate;
    auto a = [&](double t) {
      const TimeBasisSample s = basis->at(t);
      return s.gamma * kD + s.psi * rate;
    };
    auto da = [&](double t) {
      const TimeBasisSample s = basis->at(t);
      return s.dgamma * kD + s.dpsi * rate;
    };
    EXPECT_NEAR(a(0.0), 0.0, 1e-15) << p.note;
    EXPECT_NEAR(da(0.0), rate, 1e-14) << p.note;
    EXPECT_NEAR(a(1.0), kD, 1e-12 * (1.0 + basis->impulseResponseAtOne())) << p.note;
    // The analytic a' must be the derivative of a.
    for (double t : {0.2, 0.5, 0.8}) {
      const double fd = derivative(a, t, kDelta);
      EXPECT_NEAR(da(t), fd, 1e-6 * (1.0 + std::fabs(fd))) << p.note << " t=" << t;
    }
    auto residual = [&](double t) {
      const double dda = p.rho != 0.0 ? derivative(da, t, kDelta) : 0.0;
      return p.rho * dda + p.eta * da(t) + p.h * a(t);
    };
    auto scale = [&](double t) {
      const double dda = p.rho != 0.0 ? derivative(da, t, kDelta) : 0.0;
      return std::fabs(p.rho * dda) + std::fabs(p.eta * da(t)) + std::fabs(p.h * a(t));
    };
    double magnitude = 0.0;
    for (int j = 1; j <= 20; ++j) magnitude = std::max(magnitude, scale(j / 20.0));
    const double e = residual(1.0);
    for (int j = 1; j < 20; ++j) {
      const double t = j / 20.0;
      // Finite-difference error ~ delta^4 omega^5 / 30 relative to rho a'' ~ omega^2: < 1e-8 here.
      EXPECT_NEAR(residual(t), t * e, 1e-6 * magnitude) << p.note << " t=" << t;
    }
  }
}

// Near t = 0, Q = t^3/6 (1 + O(m t)) (MATH.md 5.5 step 1), so gamma/t^3, gamma'/(3 t^2) and
// gamma(2t)/(8 t^3) agree to O(m t). The closed forms cancel there (Q = (t - H - 2 kappa Q')/k loses
// eps/(k t^2)), which this catches at t = 1e-7.
TEST(TimeBasisOde, SmallTimesFollowTheCubicLaw) {
  for (const Params& p : kSecondOrder) {
    const Result<ModeTimeBasis> basis = ModeTimeBasis::create(p.rho, p.eta, p.h);
    ASSERT_TRUE(basis.ok()) << p.note;
    const double m = std::max(std::fabs(p.eta / (2 * p.rho)), std::sqrt(std::fabs(p.h / p.rho)));
    for (double t : {1e-7, 1e-5, 1e-3}) {
      if (m * t > 1e-2) continue;
      const double g3 = basis->at(t).gamma / (t * t * t);
      const double tol = 10.0 * m * t + 1e-12;
      EXPECT_NEAR(basis->at(t).dgamma / (3 * t * t) / g3, 1.0, tol) << p.note << " t=" << t;
      EXPECT_NEAR(basis->at(2 * t).gamma / (8 * t * t * t) / g3, 1.0, tol) << p.note << " t=" << t;
    }
  }
}

// Random parameters in the ranges of MATH.md 5.5: every basis is finite on [0, 1], meets the
// boundary conditions, and is continuous where the evaluation switches branch (m t = 2).
TEST(TimeBasisOde, RandomParametersFiniteAndContinuous) {
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  auto logUniform = [&](double lo, double hi) { return lo * std::pow(hi / lo, unit(rng)); };
  int checked = 0;
  for (int i = 0; i < 2000; ++i) {
    const double rho = logUniform(1e-3, 1e3);
    const double eta = unit(rng) < 0.2 ? 0.0 : logUniform(1e-4, 1e3);
    const double h = (unit(rng) < 0.5 ? -1.0 : 1.0) * logUniform(1e-6, 1e6);
    const Result<ModeTimeBasis> basis = ModeTimeBasis::create(rho, eta, h);
    // Growth modes may overflow (|h|/rho up to 1e9 gives e^{3e4}); those must fail cleanly.
    if (!basis.ok()) {
      EXPECT_EQ(basis.status().code(), StatusCode::kIllPosed) << basis.status().toString();
      EXPECT_LT(h, 0.0) << basis.status().toString();
      continue;
    }
    ++checked;
    const double h1 = basis->impulseResponseAtOne();
    for (int j = 0; j <= 64; ++j) {
      const TimeBasisSample s = basis->at(j / 64.0);
      ASSERT_TRUE(std::isfinite(s.gamma) && std::isfinite(s.dgamma) && std::isfinite(s.psi) &&
                  std::isfinite(s.dpsi))
          << "rho=" << rho << " eta=" << eta << " h=" << h << " t=" << j / 64.0;
    }
    EXPECT_NEAR(basis->at(1.0).gamma, 1.0, 1e-14) << "rho=" << rho << " eta=" << eta << " h=" << h;
    EXPECT_NEAR(basis->at(1.0).psi, 0.0, 1e-14 * (1.0 + h1)) << "rho=" << rho << " eta=" << eta;
    EXPECT_NEAR(basis->at(0.0).dpsi, 1.0, 1e-14) << "rho=" << rho << " eta=" << eta << " h=" << h;
    const double kappa = eta / (2.0 * rho);
    const double m = std::max(std::fabs(kappa), std::sqrt(std::fabs(h / rho)));
    const double t_switch = 2.0 / m;
    if (t_switch < 1.0) {
      const TimeBasisSample below = basis->at(t_switch * (1.0 - 1e-14));
      const TimeBasisSample above = basis->at(t_switch * (1.0 + 1e-14));
      const double scale = std::max(1.0, std::fabs(below.dgamma) * t_switch);
      EXPECT_NEAR(below.gamma, above.gamma, 1e-11 * scale)
          << "rho=" << rho << " eta=" << eta << " h=" << h << " t_switch=" << t_switch;
      EXPECT_NEAR(below.dgamma, above.dgamma, 1e-11 * (1.0 + std::fabs(below.dgamma)) * m)
          << "rho=" << rho << " eta=" << eta << " h=" << h << " t_switch=" << t_switch;
    }
  }
  EXPECT_GT(checked, 1500);
}

}  // namespace
}  // namespace odeskin
