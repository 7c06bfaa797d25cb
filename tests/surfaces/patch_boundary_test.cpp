// SPDX-License-Identifier: MIT
// The two ways of building a patch's boundary derivatives (MATH.md 3.7): coefficients times the
// boundary curves, and control curves with the corrected finite differences. Second divided
// differences are exact for quadratics at any spacing (errata F5, F6), the thesis's printed ones
// only when u3 = 2 u2 (resp. 1 - u5 = 2 (1 - u6)); three-point slopes are exact for quadratics,
// the thesis's one-sided slopes for straight lines only.
#include <cmath>

#include <gtest/gtest.h>

#include "engine/surfaces/patch_boundary.hpp"

namespace odeskin {
namespace {

// q(u) = a + b u + c u^2 per coordinate: q'(0) = b, q''(0) = 2c, q'(1) = b + 2c.
struct Quadratic {
  Vec3 a{0.3, -1.2, 2.0};
  Vec3 b{1.5, 0.25, -0.75};
  Vec3 c{-2.0, 0.5, 1.25};
  Vec3 at(double u) const { return a + u * b + u * u * c; }
};

Vec3 apply(const DerivativeWeights& w, const Vec3& boundary, const Vec3& near, const Vec3& far) {
  return w.boundary * boundary + w.near * near + w.far * far;
}

double distance(const Vec3& x, const Vec3& y) { return glm::length(x - y); }

TEST(PatchBoundary, CorrectedSecondDifferencesAreExactForQuadraticsAtAnySpacing) {
  const Quadratic q;
  const double spacings[][2] = {{0.1, 0.2}, {0.1, 0.35}, {0.05, 0.4}, {0.3, 0.45}};
  for (const auto& s : spacings) {
    for (SlopeRule rule : {SlopeRule::kOneSided, SlopeRule::kThreePoint}) {
      Result<ControlWeights> start = startControlWeights(s[0], s[1], rule);
      ASSERT_TRUE(start.ok());
      EXPECT_LT(distance(apply(start->second, q.at(0), q.at(s[0]), q.at(s[1])), 2.0 * q.c), 1e-12);
      // At u = 1: control curves at u5 = 1 - s[1] (far) and u6 = 1 - s[0] (near).
      Result<ControlWeights> end = endControlWeights(1.0 - s[1], 1.0 - s[0], rule);
      ASSERT_TRUE(end.ok());
      EXPECT_LT(distance(apply(end->second, q.at(1), q.at(1.0 - s[0]), q.at(1.0 - s[1])), 2.0 * q.c), 1e-10);
    }
  }
}

TEST(PatchBoundary, ThesisPrintedSecondDifferencesNeedDoubledSpacing) {
  const Quadratic q;
  // u3 = 2 u2: the printed form (Eq 4.4) is exact.
  EXPECT_LT(distance(apply(thesisStartSecondWeights(0.1, 0.2), q.at(0), q.at(0.1), q.at(0.2)), 2.0 * q.c), 1e-12);
  EXPECT_LT(distance(apply(thesisEndSecondWeights(0.8, 0.9), q.at(1), q.at(0.9), q.at(0.8)), 2.0 * q.c), 1e-10);
  // Otherwise it gives u3 / (2 u2) times the second derivative (MATH.md 3.7): here 1.75 x.
  const Vec3 printed = apply(thesisStartSecondWeights(0.1, 0.35), q.at(0), q.at(0.1), q.at(0.35));
  EXPECT_LT(distance(printed, 1.75 * 2.0 * q.c), 1e-10);
  EXPECT_GT(distance(printed, 2.0 * q.c), 1.0);
}

TEST(PatchBoundary, SlopeRules) {
  const Quadratic q;
  Result<ControlWeights> one = startControlWeights(0.1, 0.3, SlopeRule::kOneSided);
  Result<ControlWeights> three = startControlWeights(0.1, 0.3, SlopeRule::kThreePoint);
  ASSERT_TRUE(one.ok() && three.ok());
  // Three-point: exact; one-sided: off by c u2 (first-order difference).
  EXPECT_LT(distance(apply(three->first, q.at(0), q.at(0.1), q.at(0.3)), q.b), 1e-12);
  EXPECT_LT(distance(apply(one->first, q.at(0), q.at(0.1), q.at(0.3)), q.b + 0.1 * q.c), 1e-12);
  Result<ControlWeights> end3 = endControlWeights(0.6, 0.85, SlopeRule::kThreePoint);
  Result<ControlWeights> end1 = endControlWeights(0.6, 0.85, SlopeRule::kOneSided);
  ASSERT_TRUE(end3.ok() && end1.ok());
  EXPECT_LT(distance(apply(end3->first, q.at(1), q.at(0.85), q.at(0.6)), q.b + 2.0 * q.c), 1e-11);
  EXPECT_LT(distance(apply(end1->first, q.at(1), q.at(0.85), q.at(0.6)), q.b + 2.0 * q.c - 0.15 * q.c), 1e-11);
  // Both exact on a straight line.
  const Vec3 a(1, 2, 3);
  const Vec3 d(-0.5, 0.25, 2);
  auto line = [&](double u) { return a + u * d; };
  EXPECT_LT(distance(apply(one->first, line(0), line(0.1), line(0.3)), d), 1e-12);
  EXPECT_LT(distance(apply(end1->first, line(1), line(0.85), line(0.6)), d), 1e-12);
}

TEST(PatchBoundary, RejectsMisplacedControlCurves) {
  for (const auto& [a, b] : std::vector<std::pair<double, double>>{{0.0, 0.2}, {0.2, 0.2}, {0.3, 0.2}, {0.2, 1.0}, {NAN, 0.5}}) {
    EXPECT_EQ(startControlWeights(a, b, SlopeRule::kOneSided).status().code(), StatusCode::kInvalidArgument) << a << " " << b;
    EXPECT_EQ(endControlWeights(a, b, SlopeRule::kOneSided).status().code(), StatusCode::kInvalidArgument) << a << " " << b;
  }
  auto c = [](double v, int) { return Vec3(v); };
  // u3 = 0.6 > u5 = 0.5: the two pairs cross (erratum F7: 0 < u2 < u3 <= u5 < u6 < 1).
  Result<PatchCurves> crossed = controlCurveBoundary(c, c, c, c, c, c, {0.2, 0.6, 0.5, 0.8});
  EXPECT_EQ(crossed.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(crossed.status().message().find("u3 <= u5"), std::string::npos) << crossed.status().message();
  EXPECT_TRUE(controlCurveBoundary(c, c, c, c, c, c, {0.2, 0.5, 0.5, 0.8}).ok());
  EXPECT_EQ(controlCurveBoundary(c, nullptr, c, c, c, c, {}).status().code(), StatusCode::kInvalidArgument);
}

TEST(PatchBoundary, CoefficientsScaleTheBoundaryCurves) {
  auto c1 = [](double v, int order) { return order == 0 ? Vec3(std::cos(v), std::sin(v), 0.0) : Vec3(-std::sin(v), std::cos(v), 0.0); };
  auto c4 = [](double v, int) { return Vec3(2.0 * v, 1.0, -1.0); };
  Result<PatchCurves> curves = coefficientBoundary(c1, c4, {0.5, -2.0, 3.0, 0.25});
  ASSERT_TRUE(curves.ok());
  for (double v : {0.0, 0.3, 1.0}) {
    EXPECT_EQ((*curves)[1](v, 0), 0.5 * c1(v, 0));
    EXPECT_EQ((*curves)[2](v, 1), -2.0 * c1(v, 1));
    EXPECT_EQ((*curves)[4](v, 0), 3.0 * c4(v, 0));
    EXPECT_EQ((*curves)[5](v, 0), 0.25 * c4(v, 0));
  }
  EXPECT_EQ(coefficientBoundary(c1, c4, {0.5, INFINITY, 0, 0}).status().code(), StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace odeskin
