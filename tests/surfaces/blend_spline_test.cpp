// SPDX-License-Identifier: MIT
// The clamped cubic spline approximation of the cardinal functions (MATH.md 2.11) and the relative
// error of Eq 3.44 (MATH.md 2.12): exact on cubics, constraints kept exactly, error falling as
// pieces are added; the metric on hand-computed points and its rejections.
#include "engine/surfaces/cardinal_spline.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "engine/surfaces/blend_error.hpp"
#include "engine/surfaces/blend_examples.hpp"
#include "engine/surfaces/blending_surface.hpp"

namespace odeskin {
namespace {

TEST(ClampedCubicSpline, ReproducesCubicsExactly) {
  auto f = [](double u) { return 0.3 - 1.2 * u + 2.0 * u * u - 0.7 * u * u * u; };
  auto df = [](double u) { return -1.2 + 4.0 * u - 2.1 * u * u; };
  for (int n : {1, 2, 3, 7}) {
    std::vector<double> values;
    for (int j = 0; j <= n; ++j) values.push_back(f(double(j) / n));
    Result<ClampedCubicSpline> s = ClampedCubicSpline::fit(values, df(0.0), df(1.0));
    ASSERT_TRUE(s.ok());
    EXPECT_EQ(s->pieces(), std::size_t(n));
    for (int i = 0; i <= 40; ++i) {
      const double u = i / 40.0;
      EXPECT_NEAR(s->at(u), f(u), 1e-14) << n << " " << u;
      EXPECT_NEAR(s->derivative(u), df(u), 1e-13) << n << " " << u;
    }
    // Power-basis pieces evaluate to the same values (what a CAD export writes).
    for (std::size_t j = 0; j < s->pieces(); ++j) {
      const std::array<double, 4> c = s->pieceCoefficients(j);
      const double sl = 0.4, u = (double(j) + sl) / n;
      EXPECT_NEAR(c[0] + sl * (c[1] + sl * (c[2] + sl * c[3])), s->at(u), 1e-14);
    }
  }
}

TEST(ClampedCubicSpline, RejectsBadInput) {
  EXPECT_FALSE(ClampedCubicSpline::fit(std::vector<double>{1.0}, 0.0, 0.0).ok());
  EXPECT_FALSE(ClampedCubicSpline::fit(std::vector<double>{1.0, std::nan("")}, 0.0, 0.0).ok());
  EXPECT_FALSE(ClampedCubicSpline::fit(std::vector<double>{1.0, 2.0}, std::numeric_limits<double>::infinity(), 0.0).ok());
  Result<Ode4Cardinal> r = Ode4Cardinal::create(1, 1, 1);
  EXPECT_EQ(CardinalSpline::fit(*r, 0).status().code(), StatusCode::kOutOfRange);
}

// The spline keeps r_k at the knots and the end slopes, so the four constraints still hold, and
// its error falls like h^4 as pieces are added (MATH.md 2.11).
TEST(CardinalSpline, KeepsConstraintsAndConvergesWithPieces) {
  for (const auto& [alpha, beta, gamma] : {std::tuple{1.0, 0.5, 1.0}, std::tuple{1.0, 17.0, 1.0},
                                          std::tuple{1.0, -100.0, 0.0}, std::tuple{3.7, 2.0, 18.0}}) {
    Result<Ode4Cardinal> r = Ode4Cardinal::create(alpha, beta, gamma);
    ASSERT_TRUE(r.ok());
    double previous = std::numeric_limits<double>::infinity();
    for (int n : {1, 2, 4, 6, 8, 16}) {
      Result<CardinalSpline> s = CardinalSpline::fit(*r, n);
      ASSERT_TRUE(s.ok());
      const CardinalSample a0 = s->at(0.0), a1 = s->at(1.0), e0 = r->at(0.0), e1 = r->at(1.0);
      for (std::size_t k = 0; k < 4; ++k) {
        EXPECT_DOUBLE_EQ(a0.r[k], e0.r[k]);
        EXPECT_DOUBLE_EQ(a1.r[k], e1.r[k]);
        EXPECT_NEAR(a0.dr[k], e0.dr[k], 1e-13);
        EXPECT_NEAR(a1.dr[k], e1.dr[k], 1e-13);
      }
      double worst = 0.0;
      for (int i = 0; i <= 400; ++i) {
        const CardinalSample a = s->at(i / 400.0), e = r->at(i / 400.0);
        for (std::size_t k = 0; k < 4; ++k) worst = std::max(worst, std::fabs(a.r[k] - e.r[k]));
      }
      EXPECT_LT(worst, previous) << beta << " n=" << n;
      previous = worst;
    }
    EXPECT_LT(previous, beta == -100.0 ? 1e-3 : 1e-5) << beta;  // n = 16
  }
}

TEST(RelativeError, Eq344OnHandComputedPoints) {
  const std::vector<Vec3> p = {Vec3(1, 0, 0), Vec3(0, 2, 0), Vec3(0, 0, 0), Vec3(0, 0, 4)};
  const std::vector<Vec3> q = {Vec3(1.1, 0, 0), Vec3(0, 2, 0.2), Vec3(5, 5, 5), Vec3(0, 0, 4)};
  Result<RelativeError> e = relativeError(p, q);
  ASSERT_TRUE(e.ok());
  EXPECT_EQ(e->used, 3u);
  EXPECT_EQ(e->skipped, 1u);  // |p| = 0: Eq 3.44 is undefined there
  EXPECT_NEAR(e->mean, (0.1 + 0.1 + 0.0) / 3.0, 1e-15);
  EXPECT_NEAR(e->max, 0.1, 1e-15);
  EXPECT_FALSE(relativeError(p, std::vector<Vec3>(3)).ok());
  EXPECT_FALSE(relativeError(std::vector<Vec3>{}, std::vector<Vec3>{}).ok());
  EXPECT_FALSE(relativeError(std::vector<Vec3>(2), std::vector<Vec3>(2)).ok());
  Result<RelativeError> nan = relativeError(p, std::vector<Vec3>{Vec3(0), Vec3(std::nan("")), Vec3(0), Vec3(0)});
  ASSERT_FALSE(nan.ok());
  EXPECT_NE(nan.status().message().find("point 1"), std::string::npos);
}

// Table 3.1's protocol on Eq 3.18: profile and surface error fall with the number of pieces.
TEST(RelativeError, SplineBlendErrorFallsWithPieces) {
  Result<BlendExample> e = blendExample("3.18");
  ASSERT_TRUE(e.ok());
  Result<Ode4Cardinal> r = Ode4Cardinal::create(e->thesis.alpha, e->thesis.beta, e->thesis.gamma);
  Result<BlendingSurface> exact = BlendingSurface::create(e->boundary, [c = *r](double u) { return c.at(u); });
  ASSERT_TRUE(exact.ok());
  double previous_profile = 1.0, previous_surface = 1.0;
  for (int n : {2, 4, 6}) {
    Result<CardinalSpline> s = CardinalSpline::fit(*r, n);
    Result<BlendingSurface> approx = BlendingSurface::create(e->boundary, [sp = *s](double u) { return sp.at(u); });
    Result<BlendApproximationError> err = blendApproximationError(*exact, *approx);
    ASSERT_TRUE(err.ok()) << err.status().toString();
    EXPECT_EQ(err->profile.used, 100u);
    EXPECT_EQ(err->surface.used, 10000u);
    EXPECT_LT(err->profile.mean, previous_profile);
    EXPECT_LT(err->surface.mean, previous_surface);
    EXPECT_GT(err->surface.mean, 0.0);
    previous_profile = err->profile.mean;
    previous_surface = err->surface.mean;
  }
}

}  // namespace
}  // namespace odeskin
