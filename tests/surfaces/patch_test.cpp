// SPDX-License-Identifier: MIT
// One C2 patch in every regime: S, S_u and S_uu at u = 0 and u = 1 reproduce the six boundary
// curves (both ways of building them), and the v-derivatives follow the curves.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "engine/surfaces/patch.hpp"

namespace odeskin {
namespace {

// A closed rim of radius r at height z, and its v-derivatives (v in [0, 1] is once around).
PatchCurve rim(double r, double z, double wobble) {
  return [=](double v, int order) {
    const double a = 2.0 * M_PI * v;
    const double k = std::pow(2.0 * M_PI, order);
    const double radius = r + wobble * std::cos(3.0 * a);
    const double dr = -3.0 * wobble * std::sin(3.0 * a);
    const double ddr = -9.0 * wobble * std::cos(3.0 * a);
    const double c = std::cos(a), s = std::sin(a);
    if (order == 0) return Vec3(radius * c, radius * s, z);
    if (order == 1) return k * Vec3(dr * c - radius * s, dr * s + radius * c, 0.0);
    return k * Vec3(ddr * c - 2.0 * dr * s - radius * c, ddr * s + 2.0 * dr * c - radius * s, 0.0);
  };
}

std::vector<Ode6Shape> everyRegime() {
  return {{1, -5, 4},  {1, 3, 1},   {1, 0, -1},  {1, -3, 0},     {1, 3, 0},  {1, 0, 0},
          {1, -2, 1},  {1, 2, 1},   {1, 1, 1},   {1e-4, 3, 1e-4}, {1, -4e6, 0}, {1, 0, 1e8}};
}

// |S^(j)(end, v) - c(v)| relative to the size of the terms: W^j max_k |c_k(v)|, where W is the
// patch's frequency scale (g_k^(j) is of order W^j, so rounding in the sum is too).
double worstConstraintError(const Patch& patch) {
  double worst = 0.0;
  const double w = patch.cardinal().basis().w;
  for (int i = 0; i <= 16; ++i) {
    const double v = i / 16.0;
    double size = 0.0;
    for (const PatchCurve& c : patch.curves()) size = std::max(size, glm::length(c(v, 0)));
    for (int end = 0; end < 2; ++end) {
      const PatchPoint p = patch.evaluate(end, v);
      const Vec3 got[3] = {p.s, p.s_u, p.s_uu};
      for (std::size_t j = 0; j < 3; ++j) {
        const double error = glm::length(got[j] - patch.curves()[3 * static_cast<std::size_t>(end) + j](v, 0));
        worst = std::max(worst, error / (std::pow(w, static_cast<double>(j)) * size));
      }
    }
  }
  return worst;
}

TEST(Patch, CoefficientBoundaryConstraintsInEveryRegime) {
  Result<PatchCurves> curves = coefficientBoundary(rim(1.0, 0.0, 0.1), rim(0.6, -1.5, 0.05), {0.8, -1.5, 0.4, 2.0});
  ASSERT_TRUE(curves.ok());
  for (const Ode6Shape& shape : everyRegime()) {
    Result<Patch> patch = Patch::create(shape, *curves);
    ASSERT_TRUE(patch.ok()) << patch.status().toString();
    const double error = worstConstraintError(*patch);
    std::printf("coefficients, (%g, %g, %g) regime %s: worst relative constraint error %.2e\n", shape.rho, shape.eta,
                shape.lambda, ode6RegimeName(patch->cardinal().regime()), error);
    EXPECT_LE(error, 1e-12) << shape.rho << " " << shape.eta << " " << shape.lambda;
  }
}

TEST(Patch, ControlCurveBoundaryConstraintsInEveryRegime) {
  for (SlopeRule rule : {SlopeRule::kOneSided, SlopeRule::kThreePoint}) {
    Result<PatchCurves> curves = controlCurveBoundary(rim(1.0, 0.0, 0.1), rim(1.1, -0.2, 0.1), rim(1.0, -0.5, 0.0),
                                                      rim(0.7, -1.0, 0.05), rim(0.65, -1.3, 0.05), rim(0.6, -1.5, 0.05),
                                                      {0.15, 0.35, 0.6, 0.85}, rule);
    ASSERT_TRUE(curves.ok());
    for (const Ode6Shape& shape : everyRegime()) {
      Result<Patch> patch = Patch::create(shape, *curves);
      ASSERT_TRUE(patch.ok());
      EXPECT_LE(worstConstraintError(*patch), 1e-12) << shape.rho << " " << shape.eta << " " << shape.lambda;
    }
  }
}

TEST(Patch, VDerivativesFollowTheCurves) {
  Result<PatchCurves> curves = coefficientBoundary(rim(1.0, 0.0, 0.1), rim(0.6, -1.5, 0.05), {0.8, -1.5, 0.4, 2.0});
  ASSERT_TRUE(curves.ok());
  Result<Patch> patch = Patch::create({1, 3, 1}, *curves);
  ASSERT_TRUE(patch.ok());
  // Central differences of S in v against S_v and S_vv (errors h^2 |S'''| / 6 ~ 1e-6 and the
  // cancellation in the second difference ~ 1e-16 / h^2), in the interior.
  const double h = 1e-4;
  for (double u : {0.0, 0.3, 0.7, 1.0}) {
    for (double v : {0.2, 0.55}) {
      const PatchPoint p = patch->evaluate(u, v);
      const Vec3 plus = patch->position(u, v + h);
      const Vec3 minus = patch->position(u, v - h);
      EXPECT_LT(glm::length((plus - minus) / (2.0 * h) - p.s_v), 1e-5);
      EXPECT_LT(glm::length((plus - 2.0 * p.s + minus) / (h * h) - p.s_vv), 2e-4);
      EXPECT_EQ(patch->position(u, v), p.s);
    }
  }
  EXPECT_EQ(Patch::create({1, 3, 1}, PatchCurves{}).status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(Patch::create({0, 3, 1}, *curves).status().code(), StatusCode::kDegenerate);
}

}  // namespace
}  // namespace odeskin
