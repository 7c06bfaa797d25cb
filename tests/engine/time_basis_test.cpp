// SPDX-License-Identifier: MIT
// Golden vectors of the chapter-6 time basis (MATH.md 5, spec/vectors/time_basis.json) plus the
// boundary properties of MATH.md 5.2 and the material helpers of MATH.md 5.7.
#include "engine/offline/time_basis.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/offline/material.hpp"

namespace odeskin {
namespace {

nlohmann::json loadVectors() {
  std::ifstream in(ODESKIN_SPEC_DIR "/vectors/time_basis.json");
  EXPECT_TRUE(in.good()) << "cannot open " << ODESKIN_SPEC_DIR "/vectors/time_basis.json";
  return nlohmann::json::parse(in);
}

Material caseMaterial(const nlohmann::json& c) {
  Material m;
  m.rho = c.at("rho").get<double>();
  m.eta = c.at("eta").get<double>();
  m.zeta = c.at("zeta").get<double>();
  m.xi = c.at("xi").get<double>();
  return m;
}

ModeKind expectedKind(const std::string& kind) {
  if (kind == "second") return ModeKind::kSecondOrder;
  if (kind == "first") return ModeKind::kFirstOrder;
  return ModeKind::kStatic;
}

struct Worst {
  double ratio = 0.0;  // |x - ref| / (tol (1 + |ref|)), 1 = at the tolerance
  std::string where;
  double gamma = 0.0;  // largest |x - ref| / (1 + |ref|) over gamma, dgamma
  double psi = 0.0;    // same over psi, dpsi
};

void checkValue(const std::string& note, double t, const char* quantity, double value, double ref,
                double tol, Worst* worst) {
  const double err = std::fabs(value - ref);
  const double bound = tol * (1.0 + std::fabs(ref));
  EXPECT_LE(err, bound) << "case '" << note << "', t=" << t << ", " << quantity << ": got " << value
                        << ", reference " << ref;
  const double rel = err / (1.0 + std::fabs(ref));
  double& q = std::string(quantity).find("psi") != std::string::npos ? worst->psi : worst->gamma;
  q = std::max(q, rel);
  if (!(err / bound <= worst->ratio)) {
    worst->ratio = err / bound;
    worst->where = note + " t=" + std::to_string(t) + " " + quantity;
  }
}

TEST(TimeBasisVectors, AllCasesWithinTolerance) {
  const nlohmann::json doc = loadVectors();
  const std::vector<double> ts = doc.at("t").get<std::vector<double>>();
  const nlohmann::json& cases = doc.at("cases");
  ASSERT_EQ(cases.size(), 26u);
  constexpr double kTol = 1e-10;  // stated in the vector file's description
  Worst worst;
  int value_cases = 0;
  for (const nlohmann::json& c : cases) {
    const std::string note = c.at("note").get<std::string>();
    const int n = c.at("n").get<int>();
    const Result<ModeTimeBasis> basis = ModeTimeBasis::create(caseMaterial(c), n);
    if (c.at("expect_error").get<bool>()) {
      ASSERT_FALSE(basis.ok()) << "case '" << note << "' must fail";
      const std::string kind = c.at("error_kind").get<std::string>();
      const StatusCode want = kind == "resonant" ? StatusCode::kIllPosed : StatusCode::kDegenerate;
      EXPECT_EQ(basis.status().code(), want) << "case '" << note << "': " << basis.status().toString();
      EXPECT_NE(basis.status().message().find("mode " + std::to_string(n)), std::string::npos)
          << basis.status().message();
      continue;
    }
    ASSERT_TRUE(basis.ok()) << "case '" << note << "': " << basis.status().toString();
    ++value_cases;
    EXPECT_EQ(basis->kind(), expectedKind(c.at("kind").get<std::string>())) << note;
    EXPECT_EQ(basis->rateIgnored(), c.at("rate_ignored").get<bool>()) << note;
    const double h1 = c.at("H1").get<double>();
    EXPECT_LE(std::fabs(basis->impulseResponseAtOne() - h1), kTol * (1.0 + h1)) << note << ": H1";
    const double tol_psi = c.at("tol_psi").get<double>();
    for (size_t i = 0; i < ts.size(); ++i) {
      const TimeBasisSample s = basis->at(ts[i]);
      checkValue(note, ts[i], "gamma", s.gamma, c.at("gamma")[i].get<double>(), kTol, &worst);
      checkValue(note, ts[i], "dgamma", s.dgamma, c.at("dgamma")[i].get<double>(), kTol, &worst);
      checkValue(note, ts[i], "psi", s.psi, c.at("psi")[i].get<double>(), tol_psi, &worst);
      checkValue(note, ts[i], "dpsi", s.dpsi, c.at("dpsi")[i].get<double>(), tol_psi, &worst);
    }
  }
  EXPECT_EQ(value_cases, 24);
  std::printf("worst error / tolerance = %.3g at %s; worst |x-ref|/(1+|ref|): "
              "gamma,dgamma %.3g, psi,dpsi %.3g\n",
              worst.ratio, worst.where.c_str(), worst.gamma, worst.psi);
}

TEST(TimeBasisVectors, ModeStiffnessMatchesStoredH) {
  const nlohmann::json doc = loadVectors();
  for (const nlohmann::json& c : doc.at("cases")) {
    const int n = c.at("n").get<int>();
    const double h = modeStiffness(caseMaterial(c), n);
    // h_n is the exact value; zeta - 4 n^2 pi^2 xi in float64 is within a few ulps of its terms.
    const double bend = 4.0 * n * n * std::numbers::pi * std::numbers::pi * c.at("xi").get<double>();
    const double scale = std::fabs(c.at("zeta").get<double>()) + std::fabs(bend);
    EXPECT_NEAR(h, c.at("h_n").get<double>(), 4e-16 * scale + 1e-300) << c.at("note");
  }
}

TEST(TimeBasis, NonFiniteParametersAreInvalidArguments) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  struct Bad {
    double rho, eta, h;
    const char* name;
  };
  for (const Bad& b : {Bad{nan, 1, 1, "rho"}, Bad{1, nan, 1, "eta"}, Bad{1, 1, nan, "h"},
                       Bad{inf, 1, 1, "rho"}, Bad{0, -inf, 1, "eta"}, Bad{1, 1, -inf, "h"}}) {
    const Result<ModeTimeBasis> r = ModeTimeBasis::create(b.rho, b.eta, b.h, 7);
    ASSERT_FALSE(r.ok()) << b.name;
    EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument) << r.status().toString();
    EXPECT_NE(r.status().message().find(b.name), std::string::npos) << r.status().message();
    EXPECT_NE(r.status().message().find("mode 7"), std::string::npos) << r.status().message();
  }
  Material m = skinMaterial();
  m.xi = nan;
  const Result<ModeTimeBasis> r = ModeTimeBasis::create(m, 2);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(r.status().message().find("xi"), std::string::npos) << r.status().message();
  EXPECT_EQ(ModeTimeBasis::create(skinMaterial(), -1).status().code(), StatusCode::kInvalidArgument);
}

TEST(TimeBasis, ResonanceMessageNamesModeAndParameters) {
  const Result<ModeTimeBasis> r = ModeTimeBasis::create(1.0, -10.0, 46.95719084373242, 3);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kIllPosed);
  EXPECT_EQ(r.status().message(),
            "mode 3 (rho=1, eta=-10, h=46.957): resonant: P(1) = 0, the time basis would exceed 1e9");
  // Slightly off resonance the problem is well posed again.
  EXPECT_TRUE(ModeTimeBasis::create(1.0, -10.0, 46.8, 3).ok());
}

TEST(TimeBasis, SecondOrderBoundaryProperties) {
  const nlohmann::json doc = loadVectors();
  for (const nlohmann::json& c : doc.at("cases")) {
    if (c.at("expect_error").get<bool>() || c.at("kind") != "second") continue;
    const Result<ModeTimeBasis> basis = ModeTimeBasis::create(caseMaterial(c), c.at("n").get<int>());
    ASSERT_TRUE(basis.ok());
    const TimeBasisSample s0 = basis->at(0.0);
    const TimeBasisSample s1 = basis->at(1.0);
    const std::string note = c.at("note").get<std::string>();
    const double h1 = basis->impulseResponseAtOne();
    EXPECT_EQ(s0.gamma, 0.0) << note;
    EXPECT_EQ(s0.dgamma, 0.0) << note;
    EXPECT_EQ(s0.psi, 0.0) << note;
    EXPECT_NEAR(s0.dpsi, 1.0, 1e-15) << note;
    EXPECT_NEAR(s1.gamma, 1.0, 1e-15) << note;
    // psi(1) = H(1) - H(1) gamma(1) is exact up to the rounding of H(1).
    EXPECT_NEAR(s1.psi, 0.0, 1e-15 * (1.0 + h1)) << note;
  }
}

TEST(TimeBasis, FirstOrderAndStaticIgnoreTheRate) {
  const Result<ModeTimeBasis> first = ModeTimeBasis::create(0.0, 2.0, 5.0);
  ASSERT_TRUE(first.ok());
  EXPECT_EQ(first->kind(), ModeKind::kFirstOrder);
  EXPECT_TRUE(first->rateIgnored());
  EXPECT_EQ(first->at(0.0).dgamma, 0.0);
  EXPECT_NEAR(first->at(1.0).gamma, 1.0, 1e-15);
  EXPECT_EQ(first->at(0.3).psi, 0.0);
  // rho = 0, h = 0: eta a' = t e gives gamma = t^2.
  const Result<ModeTimeBasis> quad = ModeTimeBasis::create(0.0, 2.0, 0.0);
  ASSERT_TRUE(quad.ok());
  EXPECT_NEAR(quad->at(0.3).gamma, 0.09, 1e-15);
  EXPECT_NEAR(quad->at(0.3).dgamma, 0.6, 1e-15);

  const Material still = staticMaterial();
  const Result<ModeTimeBasis> stat = ModeTimeBasis::create(still.rho, still.eta, 3.0);
  ASSERT_TRUE(stat.ok());
  EXPECT_EQ(stat->kind(), ModeKind::kStatic);
  EXPECT_TRUE(stat->rateIgnored());
  EXPECT_EQ(stat->at(0.4).gamma, 0.4);
  EXPECT_EQ(stat->at(0.0).dgamma, 1.0);
  EXPECT_EQ(ModeTimeBasis::create(staticMaterial(), 0).status().code(), StatusCode::kDegenerate);
}

TEST(TimeBasis, Flags) {
  EXPECT_TRUE(ModeTimeBasis::create(1.0, -2.0, 50.0)->negativeDamping());
  EXPECT_FALSE(ModeTimeBasis::create(1.0, 2.0, 50.0)->negativeDamping());
  EXPECT_FALSE(ModeTimeBasis::create(1.0, 0.0, 50.0)->negativeDamping());
  EXPECT_TRUE(ModeTimeBasis::create(1.0, 0.5, -42.0)->growthMode());
  EXPECT_FALSE(ModeTimeBasis::create(1.0, 0.5, 42.0)->growthMode());
  EXPECT_TRUE(ModeTimeBasis::create(0.0, 2.0, -5.0)->growthMode());
  EXPECT_GT(ModeTimeBasis::create(1.0, 0.0, -400.0)->impulseResponseAtOne(), 1e7);
}

TEST(Material, ModeStiffnessSigns) {
  Material m;
  m.zeta = 100.0;
  m.xi = 0.1;
  const double bend3 = 4.0 * 9.0 * std::numbers::pi * std::numbers::pi * 0.1;  // 35.53
  EXPECT_DOUBLE_EQ(modeStiffness(m, 0), 100.0);
  EXPECT_DOUBLE_EQ(modeStiffness(m, 3), 100.0 - bend3);
  m.bending = BendingSign::kStiffening;
  EXPECT_DOUBLE_EQ(modeStiffness(m, 0), 100.0);
  EXPECT_DOUBLE_EQ(modeStiffness(m, 3), 100.0 + bend3);
}

TEST(Material, Presets) {
  const Material skin = skinMaterial();
  EXPECT_EQ(skin.rho, 1050.0);
  EXPECT_EQ(skin.eta, 0.619);
  EXPECT_EQ(skin.zeta, 1.0e4);
  // E h^3 / (12 (1 - mu^2)) = 150 * 8e-9 / 10.92 (MATH.md 5.7), as in the vector case.
  EXPECT_NEAR(skin.xi, 1.098901098901099e-07, 1e-22);
  EXPECT_EQ(skin.bending, BendingSign::kThesis);
  const Material still = staticMaterial();
  EXPECT_EQ(still.rho, 0.0);
  EXPECT_EQ(still.eta, 0.0);
  EXPECT_EQ(still.zeta, 0.0);
  EXPECT_EQ(still.xi, 0.0);
  const std::string text = describe(skin);
  EXPECT_NE(text.find("rho=1050"), std::string::npos) << text;
  EXPECT_NE(text.find("eta=0.619"), std::string::npos) << text;
  EXPECT_NE(text.find("zeta=10000"), std::string::npos) << text;
  EXPECT_NE(text.find("xi=1.0989e-07"), std::string::npos) << text;
}

}  // namespace
}  // namespace odeskin
