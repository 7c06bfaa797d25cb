// SPDX-License-Identifier: MIT
// Ode6Cardinal against every case of spec/vectors/ode6_cardinal.json (values, slopes and curvatures
// within the file's |x - ref| <= 1e-10 (1 + |ref|); resonant and degenerate cases must fail), then
// properties: the six unit conditions at u = 0, 1 in every regime, the mirror identities, the ODE
// itself (derivatives up to the sixth), scale invariance, and the quintic Hermite limit.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "engine/surfaces/ode6_cardinal.hpp"

namespace odeskin {
namespace {

using nlohmann::json;

json loadVectors() {
  std::ifstream in(std::string(ODESKIN_SPEC_DIR) + "/vectors/ode6_cardinal.json");
  EXPECT_TRUE(in.good()) << "cannot open ode6_cardinal.json";
  return json::parse(in);
}

// The file's regime strings begin with the condition; map it to ours.
std::string regimeCondition(Ode6Regime r) {
  switch (r) {
    case Ode6Regime::kA: return "D>0, c>0, b<0";
    case Ode6Regime::kB: return "D>0, c>0, b>0";
    case Ode6Regime::kC: return "D>0, c<0";
    case Ode6Regime::kD: return "c=0, b<0";
    case Ode6Regime::kE: return "c=0, b>0";
    case Ode6Regime::kF: return "b=c=0";
    case Ode6Regime::kG: return "D=0, b<0";
    case Ode6Regime::kH: return "D=0, b>0";
    case Ode6Regime::kI: return "D<0";
  }
  return "?";
}

TEST(Ode6CardinalVectors, EveryCaseWithinTheFileTolerance) {
  const json vectors = loadVectors();
  const std::vector<double> us = vectors.at("u").get<std::vector<double>>();
  const char* names[3] = {"g", "dg", "ddg"};
  double worst = 0.0;
  std::size_t checked = 0;
  std::size_t errors = 0;
  for (const json& c : vectors.at("cases")) {
    const Ode6Shape shape{c.at("rho").get<double>(), c.at("eta").get<double>(), c.at("lambda").get<double>()};
    const std::string label = c.at("note").get<std::string>();
    Result<Ode6Cardinal> g = Ode6Cardinal::create(shape);
    if (c.at("expect_error").get<bool>()) {
      ASSERT_FALSE(g.ok()) << label;
      const StatusCode expected =
          c.at("error_kind").get<std::string>() == "resonant" ? StatusCode::kIllPosed : StatusCode::kDegenerate;
      EXPECT_EQ(g.status().code(), expected) << label << ": " << g.status().toString();
      ++errors;
      continue;
    }
    ASSERT_TRUE(g.ok()) << label << ": " << g.status().toString();
    EXPECT_EQ(c.at("regime").get<std::string>().rfind(regimeCondition(g->regime()), 0), 0u)
        << label << ": ours " << ode6RegimeName(g->regime()) << ", file " << c.at("regime");
    for (std::size_t i = 0; i < us.size(); ++i) {
      std::array<Ode6Values, 3> ours{};
      g->evaluate(us[i], ours);
      for (std::size_t order = 0; order < 3; ++order) {
        for (std::size_t k = 0; k < 6; ++k) {
          const double ref = c.at(names[order]).at(i).at(k).get<double>();
          const double error = std::abs(ours[order][k] - ref) / (1.0 + std::abs(ref));
          worst = std::max(worst, error);
          EXPECT_LE(error, 1e-10) << label << ": " << names[order] << (k + 1) << "(" << us[i] << ") = "
                                  << ours[order][k] << ", reference " << ref;
          ++checked;
        }
      }
    }
    // 'gain' = max |g_k(u)| on a 65-point grid.
    double gain = 0.0;
    for (int i = 0; i <= 64; ++i) {
      for (double v : g->evaluate(i / 64.0)) gain = std::max(gain, std::abs(v));
    }
    EXPECT_NEAR(gain, c.at("gain").get<double>(), 1e-10 * c.at("gain").get<double>()) << label;
  }
  EXPECT_EQ(errors, 4u);
  EXPECT_EQ(checked, 19u * 11u * 3u * 6u);
  std::printf("ode6_cardinal.json: %zu values, worst |x - ref| / (1 + |ref|) = %.3g\n", checked, worst);
}

// One case per regime and branch, including large parameters in each branch.
std::vector<Ode6Shape> regimeShapes() {
  return {
      {1, 3, 1},        {1e-4, 3, 1e-4},  {1, 0, 0},       {1, 5, 2},         {1, 3, 0},     {1, -3, 0},
      {1, 0, 1},        {1, 1, 1},        {1, -5, 4},      {1, 0, -1},        {1, -2, 1},    {1, 2, 1},
      {1, 50, 625},     {1, -1e4, 0},     {1, -4e6, 0},    {1, 0, 1e8},       {-1, -3, -1},  {1, -400, 30000},
      {1, -800, 1e4},   {1, 20, -3e4},    {1, -2e3, 1e6},  {1e-3, 1, 1e3},    {2, 60, 0},    {1, 30, 100},
  };
}

// Row order: (value, slope, curvature) at u = 0, then at u = 1, matching c1..c6. Derivatives are
// compared with the patch's own scale: g^(j) is of order W^j near thin boundary layers, so an
// absolute `tolerance` on the j-th derivative means tolerance W^j.
void expectUnitConditions(const Ode6Cardinal& g, const Ode6Shape& shape, double tolerance) {
  for (int end = 0; end < 2; ++end) {
    std::array<Ode6Values, 3> d{};
    g.evaluate(end, d);
    for (std::size_t order = 0; order < 3; ++order) {
      for (std::size_t k = 0; k < 6; ++k) {
        const double expected = (k == 3 * static_cast<std::size_t>(end) + order) ? 1.0 : 0.0;
        EXPECT_NEAR(d[order][k], expected, tolerance * std::pow(g.basis().w, static_cast<double>(order)))
            << "rho " << shape.rho << " eta " << shape.eta << " lambda " << shape.lambda << ": g" << (k + 1)
            << " derivative " << order << " at u = " << end;
      }
    }
  }
}

TEST(Ode6Cardinal, UnitConditionsAtBothEndsInEveryRegime) {
  std::array<bool, 9> seen{};
  for (const Ode6Shape& shape : regimeShapes()) {
    Result<Ode6Cardinal> g = Ode6Cardinal::create(shape);
    ASSERT_TRUE(g.ok()) << g.status().toString();
    seen[static_cast<std::size_t>(g->regime())] = true;
    expectUnitConditions(*g, shape, 1e-12);
  }
  for (std::size_t r = 0; r < seen.size(); ++r) EXPECT_TRUE(seen[r]) << "no shape in regime " << r;
}

// Found probing against MATH.md with mpmath: from p ~ 1.5e5 in the real branch, FullPivLU's
// inverse dropped a column as below its rank threshold, and g''(0) came out as
// (-6, -3, 0.5, 6, -3, 0.5) for (1, -3e10, 0) with no error.
TEST(Ode6Cardinal, LargeRealRootsKeepTheirCurvatureConditions) {
  for (const Ode6Shape& shape : {Ode6Shape{1, -1e10, 0}, Ode6Shape{1, -3e10, 0}, Ode6Shape{1, -3e10, 1},
                                 Ode6Shape{1, -1e12, 1e22}, Ode6Shape{1, 1e11, -1e21}}) {
    Result<Ode6Cardinal> g = Ode6Cardinal::create(shape);
    ASSERT_TRUE(g.ok()) << g.status().toString();
    expectUnitConditions(*g, shape, 1e-12);
  }
}

TEST(Ode6Cardinal, UsesEveryBranch) {
  std::array<int, 3> branches{};
  for (const Ode6Shape& shape : regimeShapes()) {
    Result<Ode6Cardinal> g = Ode6Cardinal::create(shape);
    ASSERT_TRUE(g.ok());
    ++branches[static_cast<std::size_t>(g->basis().branch)];
  }
  for (int count : branches) EXPECT_GE(count, 3);
}

TEST(Ode6Cardinal, MirrorIdentities) {
  for (const Ode6Shape& shape : regimeShapes()) {
    Result<Ode6Cardinal> g = Ode6Cardinal::create(shape);
    ASSERT_TRUE(g.ok());
    for (int i = 0; i <= 20; ++i) {
      const double u = i / 20.0;
      const Ode6Values a = g->evaluate(u);
      const Ode6Values m = g->evaluate(1.0 - u);
      EXPECT_NEAR(a[3], m[0], 1e-13) << u;
      EXPECT_NEAR(a[4], -m[1], 1e-13) << u;
      EXPECT_NEAR(a[5], m[2], 1e-13) << u;
    }
  }
}

TEST(Ode6Cardinal, SolvesTheOde) {
  for (const Ode6Shape& shape : regimeShapes()) {
    Result<Ode6Cardinal> g = Ode6Cardinal::create(shape);
    ASSERT_TRUE(g.ok());
    for (int i = 1; i < 10; ++i) {
      std::array<Ode6Values, 7> d{};
      g->evaluate(i / 10.0, d);
      for (std::size_t k = 0; k < 6; ++k) {
        const double a = shape.rho * d[6][k];
        const double b = shape.eta * d[4][k];
        const double c = shape.lambda * d[2][k];
        const double size = std::abs(a) + std::abs(b) + std::abs(c);
        EXPECT_LE(std::abs(a + b + c), 1e-9 * size + 1e-300)
            << "rho " << shape.rho << " eta " << shape.eta << " lambda " << shape.lambda << " g" << (k + 1);
      }
    }
  }
}

TEST(Ode6Cardinal, OnlyTheRatiosMatter) {
  Result<Ode6Cardinal> a = Ode6Cardinal::create({1.0, 3.0, 1.0});
  Result<Ode6Cardinal> b = Ode6Cardinal::create({-0.25, -0.75, -0.25});
  ASSERT_TRUE(a.ok() && b.ok());
  for (int i = 0; i <= 10; ++i) {
    const Ode6Values x = a->evaluate(i / 10.0, 2);
    const Ode6Values y = b->evaluate(i / 10.0, 2);
    for (std::size_t k = 0; k < 6; ++k) EXPECT_DOUBLE_EQ(x[k], y[k]);
  }
}

TEST(Ode6Cardinal, QuinticHermiteAtZeroEtaAndLambda) {
  Result<Ode6Cardinal> g = Ode6Cardinal::create({2.0, 0.0, 0.0});
  ASSERT_TRUE(g.ok());
  EXPECT_EQ(g->regime(), Ode6Regime::kF);
  for (int i = 0; i <= 10; ++i) {
    const double u = i / 10.0;
    const double u3 = u * u * u;
    const Ode6Values v = g->evaluate(u);
    EXPECT_NEAR(v[0], 1.0 - 10.0 * u3 + 15.0 * u3 * u - 6.0 * u3 * u * u, 1e-14);
    EXPECT_NEAR(v[1], u - 6.0 * u3 + 8.0 * u3 * u - 3.0 * u3 * u * u, 1e-14);
    EXPECT_NEAR(v[2], 0.5 * u * u - 1.5 * u3 + 1.5 * u3 * u - 0.5 * u3 * u * u, 1e-14);
  }
}

TEST(Ode6Cardinal, RejectsBadParameters) {
  EXPECT_EQ(Ode6Cardinal::create({0.0, 3.0, 1.0}).status().code(), StatusCode::kDegenerate);
  EXPECT_EQ(Ode6Cardinal::create({1.0, std::nan(""), 1.0}).status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(Ode6Cardinal::create({1.0, 1.0, INFINITY}).status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(Ode6Cardinal::create({1e-310, 1e10, 1.0}).status().code(), StatusCode::kOutOfRange);
  EXPECT_EQ(Ode6Cardinal::create({1.0, -1e13, 0.0}).status().code(), StatusCode::kOutOfRange);
  // lambda = 0, eta = 4 pi^2 ... the resonances of MATH.md 3.5 (rho = 1): eta = 80.763, 132.87.
  Result<Ode6Cardinal> resonant = Ode6Cardinal::create({1.0, 80.76291422570652, 0.0});
  ASSERT_FALSE(resonant.ok());
  EXPECT_EQ(resonant.status().code(), StatusCode::kIllPosed);
  EXPECT_NE(resonant.status().message().find("resonant"), std::string::npos) << resonant.status().message();
  EXPECT_NE(resonant.status().message().find("80.76291422570652"), std::string::npos) << resonant.status().message();
}

}  // namespace
}  // namespace odeskin
