// SPDX-License-Identifier: MIT
// The chapter-3 cardinal functions (MATH.md 2): every case of spec/vectors/ode4_cardinal.json
// within its stated tolerance, the unit boundary conditions in every regime (degenerate ones and
// large shape parameters included), the mirror identities, an independent complex-exponential
// construction at random parameters, regime A next to the real-basis threshold against a long-double
// end-anchored solve, the Hermite limit, and the errors of MATH.md 2.7-2.8.
#include "engine/surfaces/ode4_cardinal.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <fstream>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Dense>
#include <nlohmann/json.hpp>

#include "engine/surfaces/hermite_blend.hpp"

namespace odeskin {
namespace {

constexpr double kVectorTolerance = 1e-10;  // stated in ode4_cardinal.json's description
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

nlohmann::json loadVectors() {
  std::ifstream in(ODESKIN_SPEC_DIR "/vectors/ode4_cardinal.json");
  EXPECT_TRUE(in.good()) << "cannot open " << ODESKIN_SPEC_DIR "/vectors/ode4_cardinal.json";
  return nlohmann::json::parse(in);
}

// The regime label of the vectors, mapped to MATH.md 2.3's ids.
Ode4Regime regimeOfLabel(const std::string& label) {
  if (label.rfind("D=0, b<0", 0) == 0) return Ode4Regime::kRealDoublePair;
  if (label.rfind("D=0, b>0", 0) == 0) return Ode4Regime::kImaginaryDoublePair;
  if (label.rfind("D>0, c>0, b>0", 0) == 0) return Ode4Regime::kTwoImaginaryPairs;
  if (label.rfind("D>0, c>0, b<0", 0) == 0) return Ode4Regime::kTwoRealPairs;
  if (label.rfind("D>0, c<0", 0) == 0) return Ode4Regime::kRealAndImaginary;
  if (label.rfind("D<0", 0) == 0) return Ode4Regime::kComplexQuadruple;
  if (label.rfind("c=0, b<0", 0) == 0) return Ode4Regime::kZeroAndRealPair;
  if (label.rfind("c=0, b>0", 0) == 0) return Ode4Regime::kZeroAndImaginaryPair;
  if (label.rfind("b=c=0", 0) == 0) return Ode4Regime::kQuadrupleZero;
  ADD_FAILURE() << "unknown regime label " << label;
  return Ode4Regime::kQuadrupleZero;
}

TEST(Ode4CardinalVectors, EveryCaseWithinTolerance) {
  const nlohmann::json doc = loadVectors();
  const std::vector<double> us = doc.at("u").get<std::vector<double>>();
  ASSERT_EQ(doc.at("cases").size(), 45u);
  double worst = 0.0;
  std::string worst_case;
  int checked = 0;
  for (const nlohmann::json& c : doc.at("cases")) {
    const double alpha = c.at("alpha"), beta = c.at("beta"), gamma = c.at("gamma");
    const std::string note = c.at("note");
    Result<Ode4Cardinal> r = Ode4Cardinal::create(alpha, beta, gamma);
    if (c.at("expect_error").get<bool>()) {
      ASSERT_FALSE(r.ok()) << note;
      const std::string kind = c.at("error_kind");
      EXPECT_EQ(r.status().code(), kind == "resonant" ? StatusCode::kIllPosed : StatusCode::kDegenerate)
          << note << ": " << r.status().toString();
      continue;
    }
    ASSERT_TRUE(r.ok()) << note << ": " << r.status().toString();
    EXPECT_EQ(r->regime(), regimeOfLabel(c.at("regime"))) << note << ": " << ode4RegimeName(r->regime());
    for (std::size_t i = 0; i < us.size(); ++i) {
      const CardinalSample s = r->at(us[i]);
      for (std::size_t k = 0; k < 4; ++k) {
        const double ref_r = c.at("r")[i][k], ref_dr = c.at("dr")[i][k];
        for (const auto& [got, ref, what] : {std::tuple{s.r[k], ref_r, "r"}, std::tuple{s.dr[k], ref_dr, "dr"}}) {
          const double rel = std::fabs(got - ref) / (1.0 + std::fabs(ref));
          EXPECT_LE(rel, kVectorTolerance) << note << ": " << what << k + 1 << "(" << us[i] << ") = " << got
                                           << ", reference " << ref;
          if (rel > worst) {
            worst = rel;
            worst_case = note;
          }
        }
      }
    }
    ++checked;
  }
  EXPECT_EQ(checked, 38);
  std::printf("worst |x - ref| / (1 + |ref|) over %d cases: %.2e (%s)\n", checked, worst, worst_case.c_str());
}

// gain = max over k and u = i/64 of |r_k(u)| (MATH.md 2.7's independent resonance indicator).
TEST(Ode4CardinalVectors, GainMatchesReference) {
  const nlohmann::json doc = loadVectors();
  for (const nlohmann::json& c : doc.at("cases")) {
    if (c.at("expect_error").get<bool>()) continue;
    Result<Ode4Cardinal> r = Ode4Cardinal::create(c.at("alpha"), c.at("beta"), c.at("gamma"));
    ASSERT_TRUE(r.ok());
    double gain = 0.0;
    for (int i = 0; i <= 64; ++i) {
      const CardinalSample s = r->at(i / 64.0);
      for (double x : s.r) gain = std::max(gain, std::fabs(x));
    }
    const double ref = c.at("gain");
    EXPECT_NEAR(gain, ref, 1e-9 * ref) << c.at("note").get<std::string>();
  }
}

struct Params {
  double alpha, beta, gamma;
  Ode4Regime regime;
};

// Every regime of MATH.md 2.3, the degenerate-but-regular ones of 2.8, negative alpha, the
// double-root lines, and shape parameters far beyond the vectors' (p up to 1e5, q up to 1e3).
const std::vector<Params> kEveryRegime = {
    {1, -5, 4, Ode4Regime::kTwoRealPairs},
    {1, -1e10, 1, Ode4Regime::kTwoRealPairs},
    {1, 3, 1, Ode4Regime::kTwoImaginaryPairs},
    {1, 1e6, 1e4, Ode4Regime::kTwoImaginaryPairs},
    {1, 3, -4, Ode4Regime::kRealAndImaginary},
    {1, 0, -1e8, Ode4Regime::kRealAndImaginary},
    {1, 1e5, -1e12, Ode4Regime::kRealAndImaginary},
    {1, -4, 0, Ode4Regime::kZeroAndRealPair},
    {1, -4e6, 0, Ode4Regime::kZeroAndRealPair},
    {1, -1e10, 0, Ode4Regime::kZeroAndRealPair},
    {1, 4, 0, Ode4Regime::kZeroAndImaginaryPair},
    {1e-3, 1e-1, 0, Ode4Regime::kZeroAndImaginaryPair},
    {1, 0, 0, Ode4Regime::kQuadrupleZero},
    {-7, 0, 0, Ode4Regime::kQuadrupleZero},
    {1, -2, 1, Ode4Regime::kRealDoublePair},
    {1, -2e6, 1e12, Ode4Regime::kRealDoublePair},
    {1, 2, 1, Ode4Regime::kImaginaryDoublePair},
    {1, 2e4, 1e8, Ode4Regime::kImaginaryDoublePair},
    {1, 1, 1, Ode4Regime::kComplexQuadruple},
    {-1, -1, -1, Ode4Regime::kComplexQuadruple},
    {1, 0, 1e12, Ode4Regime::kComplexQuadruple},   // the largest |gamma/alpha| accepted
    {1, -1e3, 1e9, Ode4Regime::kComplexQuadruple},
    {1e-6, 1e-6, 1e-6, Ode4Regime::kComplexQuadruple},
};

// r_k(0), r_k'(0), r_k(1), r_k'(1) are the unit vectors of MATH.md 2.1's table. Values to 1e-12;
// slopes to 1e-12 of the slope scale max(1, max_u |r'|), which is ~p in a boundary layer of width
// 1/p (a slope there is the difference of O(p) terms).
TEST(Ode4Cardinal, UnitConditionsInEveryRegime) {
  double worst_value = 0.0, worst_slope = 0.0, worst_relative_slope = 0.0;
  for (const Params& p : kEveryRegime) {
    SCOPED_TRACE(::testing::Message() << "(alpha, beta, gamma) = (" << p.alpha << ", " << p.beta << ", " << p.gamma << ")");
    Result<Ode4Cardinal> r = Ode4Cardinal::create(p.alpha, p.beta, p.gamma);
    ASSERT_TRUE(r.ok()) << r.status().toString();
    EXPECT_EQ(r->regime(), p.regime) << ode4RegimeName(r->regime());
    double slope_scale = 1.0;
    for (int i = 0; i <= 2000; ++i) {
      for (double d : r->at(i / 2000.0).dr) slope_scale = std::max(slope_scale, std::fabs(d));
    }
    const CardinalSample s0 = r->at(0.0);
    const CardinalSample s1 = r->at(1.0);
    for (int k = 0; k < 4; ++k) {
      const auto K = static_cast<std::size_t>(k);
      EXPECT_NEAR(s0.r[K], k == 0 ? 1.0 : 0.0, 1e-12) << "r" << k + 1 << "(0)";
      EXPECT_NEAR(s0.dr[K], k == 1 ? 1.0 : 0.0, 1e-12 * slope_scale) << "r" << k + 1 << "'(0)";
      EXPECT_NEAR(s1.r[K], k == 2 ? 1.0 : 0.0, 1e-12) << "r" << k + 1 << "(1)";
      EXPECT_NEAR(s1.dr[K], k == 3 ? 1.0 : 0.0, 1e-12 * slope_scale) << "r" << k + 1 << "'(1)";
      const double value_error = std::max(std::fabs(s0.r[K] - (k == 0)), std::fabs(s1.r[K] - (k == 2)));
      const double slope_error = std::max(std::fabs(s0.dr[K] - (k == 1)), std::fabs(s1.dr[K] - (k == 3)));
      worst_value = std::max(worst_value, value_error);
      worst_slope = std::max(worst_slope, slope_error);
      worst_relative_slope = std::max(worst_relative_slope, slope_error / slope_scale);
      for (int i = 0; i <= 100; ++i) {
        const CardinalSample s = r->at(i / 100.0);
        ASSERT_TRUE(std::isfinite(s.r[K]) && std::isfinite(s.dr[K])) << "u = " << i / 100.0;
      }
    }
  }
  std::printf("unit conditions over %zu parameter sets: values within %.2e, slopes within %.2e (%.2e of the slope scale)\n",
              kEveryRegime.size(), worst_value, worst_slope, worst_relative_slope);
}

// r3(u) = r1(1-u), r4(u) = -r2(1-u) (MATH.md 2.1), and r1 + r3 = 1 exactly when c = 0 (MATH.md 2.14).
TEST(Ode4Cardinal, MirrorIdentitiesAndPartitionOfUnity) {
  for (const Params& p : kEveryRegime) {
    Result<Ode4Cardinal> r = Ode4Cardinal::create(p.alpha, p.beta, p.gamma);
    ASSERT_TRUE(r.ok());
    double worst_sum = 0.0;
    for (int i = 0; i <= 50; ++i) {
      const double u = i / 50.0;
      const CardinalSample a = r->at(u);
      const CardinalSample b = r->at(1.0 - u);
      EXPECT_NEAR(a.r[2], b.r[0], 1e-12) << p.beta << " " << p.gamma << " u=" << u;
      EXPECT_NEAR(a.r[3], -b.r[1], 1e-12) << p.beta << " " << p.gamma << " u=" << u;
      worst_sum = std::max(worst_sum, std::fabs(a.r[0] + a.r[2] - 1.0));
    }
    if (r->c() == 0.0) {
      EXPECT_LT(worst_sum, 1e-12) << p.beta;
    } else if (std::fabs(r->c()) > 1e-3 * std::max(1.0, std::fabs(r->b()))) {
      EXPECT_GT(worst_sum, 1e-6) << p.beta << " " << p.gamma;
    }
  }
}

// MATH.md 2.4 with the complex exponential system e^{r_j u} (distinct roots only) and a 4x4 LU
// solve: independent of the even/odd blocks and the branch thresholds.
std::vector<CardinalSample> complexReference(double b, double c, const std::vector<double>& us) {
  using C = std::complex<double>;
  const C sqrt_d = std::sqrt(C(b * b - 4.0 * c));
  const C s1 = (-b + sqrt_d) / 2.0, s2 = (-b - sqrt_d) / 2.0;
  const C roots[4] = {std::sqrt(s1), -std::sqrt(s1), std::sqrt(s2), -std::sqrt(s2)};
  Eigen::Matrix4cd m;
  for (int j = 0; j < 4; ++j) {
    m(0, j) = 1.0;
    m(1, j) = roots[j];
    m(2, j) = std::exp(roots[j]);
    m(3, j) = roots[j] * std::exp(roots[j]);
  }
  const Eigen::Matrix4cd a = m.fullPivLu().inverse();
  std::vector<CardinalSample> out;
  for (double u : us) {
    CardinalSample s;
    for (int k = 0; k < 4; ++k) {
      C v = 0.0, d = 0.0;
      for (int j = 0; j < 4; ++j) {
        v += a(j, k) * std::exp(roots[j] * u);
        d += a(j, k) * roots[j] * std::exp(roots[j] * u);
      }
      s.r[static_cast<std::size_t>(k)] = v.real();
      s.dr[static_cast<std::size_t>(k)] = d.real();
    }
    out.push_back(s);
  }
  return out;
}

TEST(Ode4Cardinal, AgreesWithComplexExponentialsAtRandomParameters) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> bd(-60.0, 35.0), cd(-400.0, 400.0);
  std::vector<double> us;
  for (int i = 0; i <= 20; ++i) us.push_back(i / 20.0);
  int tested = 0;
  double worst = 0.0;
  while (tested < 300) {
    const double b = bd(rng), c = cd(rng);
    const double d = b * b - 4.0 * c;
    if (std::fabs(d) < 1e-2 || std::fabs(c) < 1e-2) continue;  // distinct nonzero roots for the reference
    Result<Ode4Cardinal> r = Ode4Cardinal::create(1.0, b, c);
    if (!r.ok()) {
      // Random draws inside MATH.md 2.7's resonance-prone regimes may land near a resonance curve.
      EXPECT_EQ(r.status().code(), StatusCode::kIllPosed);
      continue;
    }
    const std::vector<CardinalSample> ref = complexReference(b, c, us);
    double gain = 1.0;
    for (const CardinalSample& s : ref) for (double x : s.r) gain = std::max(gain, std::fabs(x));
    if (gain > 1e4) continue;  // the LU reference itself is then only good to ~1e-12 gain
    for (std::size_t i = 0; i < us.size(); ++i) {
      const CardinalSample s = r->at(us[i]);
      for (std::size_t k = 0; k < 4; ++k) {
        const double e = std::max(std::fabs(s.r[k] - ref[i].r[k]) / (1.0 + std::fabs(ref[i].r[k])),
                                  std::fabs(s.dr[k] - ref[i].dr[k]) / (1.0 + std::fabs(ref[i].dr[k])));
        worst = std::max(worst, e / gain);
        EXPECT_LT(e, 1e-9 * gain) << "b=" << b << " c=" << c << " u=" << us[i] << " k=" << k;
      }
    }
    ++tested;
  }
  std::printf("random (b, c): worst deviation from the complex-exponential reference %.2e (per gain)\n", worst);
}

// Regime A (roots +-p1, +-p2, both real) by MATH.md 2.4 with the end-anchored system
// e^{-p_j u}, e^{-p_j (1-u)}, every function at most 1 on [0, 1], and a full 4x4 LU solve in
// long double: independent of the even/odd blocks, the scaled Ch/Sh and the basis choice.
std::vector<CardinalSample> anchoredReference(double b, double c, const std::vector<double>& us) {
  using LD = long double;
  const LD sqrt_d = std::sqrt(static_cast<LD>(b) * b - 4.0L * c);
  const LD s1 = (-static_cast<LD>(b) + sqrt_d) / 2.0L;
  const LD p[2] = {std::sqrt(s1), std::sqrt(static_cast<LD>(c) / s1)};
  Eigen::Matrix<LD, 4, 4> m;
  for (int j = 0; j < 2; ++j) {
    const LD e = std::exp(-p[j]);
    m.col(2 * j) << 1.0L, -p[j], e, -p[j] * e;       // e^{-p u}
    m.col(2 * j + 1) << e, p[j] * e, 1.0L, p[j];     // e^{-p (1-u)}
  }
  const Eigen::Matrix<LD, 4, 4> a = m.fullPivLu().inverse();
  std::vector<CardinalSample> out;
  for (double u : us) {
    CardinalSample s;
    for (int k = 0; k < 4; ++k) {
      LD v = 0.0L, d = 0.0L;
      for (int j = 0; j < 2; ++j) {
        const LD left = std::exp(-p[j] * u), right = std::exp(-p[j] * (1.0L - u));
        v += a(2 * j, k) * left + a(2 * j + 1, k) * right;
        d += p[j] * (a(2 * j + 1, k) * right - a(2 * j, k) * left);
      }
      s.r[static_cast<std::size_t>(k)] = static_cast<double>(v);
      s.dr[static_cast<std::size_t>(k)] = static_cast<double>(d);
    }
    out.push_back(s);
  }
  return out;
}

// The band of regime A next to the real-basis threshold (D just below omega^4/4) where the pq
// basis's two growth rates p1 = P + Q and p2 = P - Q differ by a large 2Q: its Hadamard ratio
// fell to ~1e-10 (b -7000 to -30000, c 1e7 to 2e8, misses up to 1.4e-5 in `blend`), and further
// out (|b| >= 1e5) it reported these never-resonant parameters (MATH.md 2.7) as resonant.
TEST(Ode4Cardinal, RegimeANextToTheRealBasisThreshold) {
  std::vector<std::pair<double, double>> bc = {{-30000, 2e8}};  // the worst miss in `blend`
  for (int i = 0; i <= 12; ++i) {
    for (int j = 0; j <= 12; ++j) {
      bc.emplace_back(-7000.0 * std::pow(30000.0 / 7000.0, i / 12.0), 1e7 * std::pow(20.0, j / 12.0));
    }
  }
  bc.insert(bc.end(), {{-1e5, 2e9}, {-1e6, 2e11}, {-2e6, 9e11}});
  std::vector<double> us;
  for (int i = 0; i <= 40; ++i) us.push_back(i / 40.0);
  int tested = 0;
  double worst_unit = 0.0, worst_reference = 0.0;
  for (const auto& [b, c] : bc) {
    if (b * b - 4.0 * c < 1e-6 * b * b) continue;  // regime I or G, or too near it for the reference
    SCOPED_TRACE(::testing::Message() << "b = " << b << ", c = " << c);
    Result<Ode4Cardinal> r = Ode4Cardinal::create(1.0, b, c);
    ASSERT_TRUE(r.ok()) << r.status().toString();
    ASSERT_EQ(r->regime(), Ode4Regime::kTwoRealPairs);
    const std::vector<CardinalSample> ref = anchoredReference(b, c, us);
    // MATH.md 2.5's W: slopes are differences of terms of that size (layers of width 1/sqrt(|b|)).
    const double slope_scale = std::max(1.0, std::sqrt(-b));
    const CardinalSample s0 = r->at(0.0), s1 = r->at(1.0);
    for (std::size_t k = 0; k < 4; ++k) {
      const double unit = std::max({std::fabs(s0.r[k] - (k == 0)), std::fabs(s1.r[k] - (k == 2)),
                                    std::fabs(s0.dr[k] - (k == 1)) / slope_scale, std::fabs(s1.dr[k] - (k == 3)) / slope_scale});
      worst_unit = std::max(worst_unit, unit);
      EXPECT_LT(unit, 1e-12) << "r" << k + 1;
    }
    for (std::size_t i = 0; i < us.size(); ++i) {
      const CardinalSample s = r->at(us[i]);
      for (std::size_t k = 0; k < 4; ++k) {
        const double e = std::max(std::fabs(s.r[k] - ref[i].r[k]), std::fabs(s.dr[k] - ref[i].dr[k]) / slope_scale);
        worst_reference = std::max(worst_reference, e);
        EXPECT_LT(e, 1e-12) << "u = " << us[i] << ", r" << k + 1;
      }
    }
    ++tested;
  }
  EXPECT_GT(tested, 60);
  std::printf("regime A band, %d (b, c): unit conditions within %.2e, reference within %.2e (slopes per W)\n",
              tested, worst_unit, worst_reference);
}

TEST(Ode4Cardinal, BasisBranchesFollowTheThresholds) {
  EXPECT_EQ(Ode4Cardinal::create(1, 0.5, 0.5)->basis(), Ode4Basis::kSeries);     // omega <= 1
  EXPECT_EQ(Ode4Cardinal::create(1, -5, 4)->basis(), Ode4Basis::kReal);         // D = 9 >= 25/4
  EXPECT_EQ(Ode4Cardinal::create(1, -4e6, 0)->basis(), Ode4Basis::kReal);
  EXPECT_EQ(Ode4Cardinal::create(1, 2, 1)->basis(), Ode4Basis::kPq);            // D = 0
  EXPECT_EQ(Ode4Cardinal::create(1, 1, 1)->basis(), Ode4Basis::kSeries);
  EXPECT_EQ(Ode4Cardinal::create(1, 0, 1e8)->basis(), Ode4Basis::kPq);          // D < 0
  // Regime A below D = omega^4/4: pq while Q = sqrt(X2) is small, real once its ratio is the better.
  EXPECT_EQ(Ode4Cardinal::create(1, -20000, 0.9999e8)->basis(), Ode4Basis::kPq);   // Q = 0.5
  EXPECT_EQ(Ode4Cardinal::create(1, -30000, 2e8)->basis(), Ode4Basis::kReal);      // Q = 20
}

// Across the double-root lines D = 0 the functions are continuous: no branch switch in the pq basis.
TEST(Ode4Cardinal, ContinuousAcrossDoubleRootLines) {
  for (double b : {2.0, -2.0, 200.0, -20000.0}) {
    const double c = b * b / 4.0;
    Result<Ode4Cardinal> mid = Ode4Cardinal::create(1, b, c);
    ASSERT_TRUE(mid.ok());
    for (double eps : {-1e-9, 1e-9}) {
      Result<Ode4Cardinal> near = Ode4Cardinal::create(1, b * (1.0 + eps), c);
      ASSERT_TRUE(near.ok());
      for (int i = 0; i <= 10; ++i) {
        const CardinalSample a = mid->at(i / 10.0), n = near->at(i / 10.0);
        for (std::size_t k = 0; k < 4; ++k) EXPECT_NEAR(a.r[k], n.r[k], 1e-6) << b << " " << eps;
      }
    }
  }
}

// MATH.md 2.9: exactly the cubic Hermite functions for beta = gamma = 0 (any alpha), and their
// limit when alpha dominates; alpha = beta = 1, gamma = 0.1 is close but not equal (C13: 2.8e-3).
TEST(Ode4Cardinal, HermiteLimit) {
  auto deviation = [](const Ode4Cardinal& r) {
    double worst = 0.0;
    for (int i = 0; i <= 200; ++i) {
      const double u = i / 200.0;
      const CardinalSample a = r.at(u), h = hermiteCardinals(u);
      for (std::size_t k = 0; k < 4; ++k) {
        worst = std::max({worst, std::fabs(a.r[k] - h.r[k]), std::fabs(a.dr[k] - h.dr[k]) / 6.0});
      }
    }
    return worst;
  };
  for (double alpha : {1.0, -2.5, 1e-3, 1e6}) {
    Result<Ode4Cardinal> r = Ode4Cardinal::create(alpha, 0.0, 0.0);
    ASSERT_TRUE(r.ok());
    EXPECT_LT(deviation(*r), 1e-14) << alpha;
  }
  double previous = 1.0;
  for (double alpha : {1e2, 1e4, 1e6, 1e8}) {
    const double d = deviation(*Ode4Cardinal::create(alpha, 1.0, 1.0));
    EXPECT_LT(d, 10.0 / alpha) << alpha;  // first order in (beta, gamma)/alpha
    EXPECT_LT(d, previous);
    previous = d;
  }
  const double c13 = deviation(*Ode4Cardinal::create(1.0, 1.0, 0.1));
  EXPECT_GT(c13, 2.7e-3);
  EXPECT_LT(c13, 2.9e-3);
}

TEST(Ode4Cardinal, RejectsNonFiniteParametersNamingThem) {
  const double inf = std::numeric_limits<double>::infinity();
  const struct {
    double alpha, beta, gamma;
    const char* message;
  } cases[] = {{kNaN, 1, 1, "alpha is NaN"}, {1, kNaN, 1, "beta is NaN"},   {1, 1, kNaN, "gamma is NaN"},
               {inf, 1, 1, "alpha is infinite"}, {1, -inf, 1, "beta is infinite"}, {1, 1, inf, "gamma is infinite"},
               {1e-300, 1e200, 1, "beta/alpha"}, {1e-200, 1e-200, 1e200, "gamma/alpha"},
               // Accepted up to 1e300 before, where from 1e16 the blends missed their constraints.
               {1, 0, 1.0000000000000002e12, "gamma/alpha = 1000000000000.0002 is outside [-1e12, 1e12]"},
               {1, 0, -1e30, "gamma/alpha = -1e+30 is outside [-1e12, 1e12]"},
               {2, 2e20, 2e40, "gamma/alpha"}};
  for (const auto& c : cases) {
    Result<Ode4Cardinal> r = Ode4Cardinal::create(c.alpha, c.beta, c.gamma);
    ASSERT_FALSE(r.ok()) << c.message;
    EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
    EXPECT_NE(r.status().message().find(c.message), std::string::npos) << r.status().message();
  }
}

TEST(Ode4Cardinal, RejectsDegenerateAndResonantParameters) {
  Result<Ode4Cardinal> second_order = Ode4Cardinal::create(0.0, -1.0, 2.0);
  ASSERT_FALSE(second_order.ok());
  EXPECT_EQ(second_order.status().code(), StatusCode::kDegenerate);
  EXPECT_NE(second_order.status().message().find("alpha = 0"), std::string::npos);
  Result<Ode4Cardinal> zero = Ode4Cardinal::create(0.0, 0.0, 0.0);
  ASSERT_FALSE(zero.ok());
  EXPECT_NE(zero.status().message().find("alpha = beta = gamma = 0"), std::string::npos);
  // gamma = 0, beta = 4 pi^2 alpha: the clamped buckling mode 1 - cos 2 pi u (symmetric).
  Result<Ode4Cardinal> buckling = Ode4Cardinal::create(2.0, 8.0 * std::numbers::pi * std::numbers::pi, 0.0);
  ASSERT_FALSE(buckling.ok());
  EXPECT_EQ(buckling.status().code(), StatusCode::kIllPosed);
  EXPECT_NE(buckling.status().message().find("resonant"), std::string::npos) << buckling.status().message();
  EXPECT_NE(buckling.status().message().find("symmetric (even)"), std::string::npos) << buckling.status().message();
  // Near (not on) a resonance the problem is well-posed and the functions are merely large.
  Result<Ode4Cardinal> near = Ode4Cardinal::create(1.0, 4.0 * std::numbers::pi * std::numbers::pi * (1 + 1e-6), 0.0);
  ASSERT_TRUE(near.ok()) << near.status().toString();
  EXPECT_LT(near->hadamardRatio(), 1e-5);
}

}  // namespace
}  // namespace odeskin
