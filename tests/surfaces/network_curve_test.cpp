// SPDX-License-Identifier: MIT
// The curves of a network: C2 cubic splines through their points. They pass through every point,
// their value, slope and curvature are continuous at every knot (the third derivative is not, so
// the comparison can tell), and they reproduce what they should exactly: straight lines, and for
// not-a-knot ends any cubic.
#include <cmath>

#include <gtest/gtest.h>

#include "engine/surfaces/network_curve.hpp"

namespace odeskin {
namespace {

std::vector<Vec3> samples(std::size_t n, bool closed, double span, Vec3 (*f)(double)) {
  std::vector<Vec3> p;
  for (std::size_t i = 0; i < n; ++i) p.push_back(f(span * static_cast<double>(i) / static_cast<double>(closed ? n : n - 1)));
  return p;
}

Vec3 wavy(double v) { return {std::cos(2.0 * v) + 0.3 * std::sin(5.0 * v), std::sin(2.0 * v), 0.2 * v * v}; }
Vec3 cubic(double v) { return {1.0 - v + 0.5 * v * v * v, 2.0 * v * v, -0.25 * v * v * v + v}; }

TEST(NetworkCurve, InterpolatesAndIsC2AtKnots) {
  for (bool closed : {false, true}) {
    const double span = 3.0;
    const std::vector<Vec3> points = samples(11, closed, span, wavy);
    Result<NetworkCurve> c = NetworkCurve::interpolate(points, closed, span);
    ASSERT_TRUE(c.ok()) << c.status().toString();
    const std::size_t spans = closed ? 11 : 10;
    double third_jump = 0.0;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const double v = span * static_cast<double>(i) / static_cast<double>(spans);
      EXPECT_LT(glm::length(c->evaluate(v) - points[i]), 1e-14);
      if (i == 0 && !closed) continue;
      for (int order = 0; order <= 2; ++order) {
        const Vec3 left = c->evaluate(v, order, true);
        const Vec3 right = c->evaluate(v, order, false);
        EXPECT_LT(glm::length(left - right), 1e-12 * (1.0 + glm::length(right))) << "knot " << i << " order " << order;
      }
      third_jump = std::max(third_jump, glm::length(c->evaluate(v, 3, true) - c->evaluate(v, 3, false)));
    }
    EXPECT_GT(third_jump, 1e-3);  // a cubic spline, not C3: the same comparison sees a jump
    if (closed) {
      // Periodic: v and v + span are the same point, with the same derivatives.
      for (int order = 0; order <= 2; ++order) EXPECT_LT(glm::length(c->evaluate(0.7, order) - c->evaluate(3.7, order)), 1e-12);
    }
  }
}

TEST(NetworkCurve, ReproducesCubicsAndLines) {
  Result<NetworkCurve> c = NetworkCurve::interpolate(samples(6, false, 2.0, cubic), false, 2.0);
  ASSERT_TRUE(c.ok());
  for (int i = 0; i <= 40; ++i) {
    const double v = i / 20.0;
    EXPECT_LT(glm::length(c->evaluate(v) - cubic(v)), 1e-13) << v;
    EXPECT_LT(glm::length(c->evaluate(v, 1) - Vec3(-1.0 + 1.5 * v * v, 4.0 * v, -0.75 * v * v + 1.0)), 1e-12) << v;
  }
  const std::vector<Vec3> line = {{0, 0, 0}, {1, 2, 3}};
  Result<NetworkCurve> l = NetworkCurve::interpolate(line, false, 1.0);
  ASSERT_TRUE(l.ok());
  EXPECT_LT(glm::length(l->evaluate(0.25) - Vec3(0.25, 0.5, 0.75)), 1e-15);
  EXPECT_LT(glm::length(l->evaluate(0.6, 2)), 1e-14);
}

TEST(NetworkCurve, RejectsBadInput) {
  const std::vector<Vec3> two = {{0, 0, 0}, {1, 0, 0}};
  EXPECT_EQ(NetworkCurve::interpolate(two, true, 1.0).status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(NetworkCurve::interpolate(std::span<const Vec3>(two.data(), 1), false, 1.0).status().code(),
            StatusCode::kInvalidArgument);
  EXPECT_EQ(NetworkCurve::interpolate(two, false, 0.0).status().code(), StatusCode::kInvalidArgument);
  const std::vector<Vec3> bad = {{0, 0, 0}, {NAN, 0, 0}};
  EXPECT_EQ(NetworkCurve::interpolate(bad, false, 1.0).status().code(), StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace odeskin
