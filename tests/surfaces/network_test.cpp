// SPDX-License-Identifier: MIT
// Patch networks (MATH.md 3.8): the jumps of S, S_u, S_uu across shared u-boundaries and of S, S_v,
// S_vv (and S_u, S_uu, S_uv) across shared v-edges are zero to rounding, with every way of giving
// boundary derivatives and different shapes row to row; the builder refuses v-pairings that cannot
// be C2 (erratum F9) unless told to warn; edits report exactly the patches they change.
#include <cstdio>

#include <gtest/gtest.h>

#include "engine/surfaces/network.hpp"
#include "surfaces/network_fixtures.hpp"

namespace odeskin {
namespace {

using testing::SweptSurface;
using testing::mixedRowShapes;
using testing::sweptLayouts;
using testing::sweptNetwork;

Network build(const NetworkDescription& d) {
  std::vector<std::string> warnings;
  Result<Network> n = Network::build(d, &warnings);
  EXPECT_TRUE(n.ok()) << n.status().toString();
  EXPECT_TRUE(warnings.empty());
  return std::move(n).value();
}

struct Jumps {
  std::array<double, 6> worst{};  // S, S_u, S_uu, S_v, S_vv, S_uv, each / the largest |value| seen
  std::array<double, 6> size{};
  void add(const PatchPoint& a, const PatchPoint& b) {
    const Vec3 x[6] = {a.s, a.s_u, a.s_uu, a.s_v, a.s_vv, a.s_uv};
    const Vec3 y[6] = {b.s, b.s_u, b.s_uu, b.s_v, b.s_vv, b.s_uv};
    for (std::size_t i = 0; i < 6; ++i) {
      worst[i] = std::max(worst[i], glm::length(x[i] - y[i]));
      size[i] = std::max({size[i], glm::length(x[i]), glm::length(y[i])});
    }
  }
  double relative(std::size_t i) const { return worst[i] / size[i]; }
};

TEST(Network, C2AcrossSharedUBoundaries) {
  for (const SweptSurface& s : sweptLayouts()) {
    const Network n = build(sweptNetwork(s, mixedRowShapes()));
    Jumps jumps;
    const std::uint32_t interfaces = s.closed_u ? n.rows() : n.rows() - 1;
    for (std::uint32_t r = 0; r < interfaces; ++r) {
      for (std::uint32_t c = 0; c < n.columns(); ++c) {
        for (int i = 0; i <= 20; ++i) {
          const double v = i / 20.0;
          jumps.add(n.evaluate(r, c, 1.0, v), n.evaluate((r + 1) % n.rows(), c, 0.0, v));
        }
      }
    }
    std::printf("u-boundaries (%s): relative jumps S %.1e, S_u %.1e, S_uu %.1e\n",
                s.closed_u ? "torus" : s.closed_v ? "tube" : "sheet", jumps.relative(0), jumps.relative(1),
                jumps.relative(2));
    // Rounding in sums of six terms whose cardinal values are exact to ~1e-15.
    EXPECT_LE(jumps.relative(0), 1e-14);
    EXPECT_LE(jumps.relative(1), 1e-13);
    EXPECT_LE(jumps.relative(2), 1e-13);
  }
}

TEST(Network, C2AcrossSharedVEdges) {
  for (const SweptSurface& s : sweptLayouts()) {
    const Network n = build(sweptNetwork(s, mixedRowShapes()));
    Jumps jumps;
    const std::uint32_t edges = s.closed_v ? n.columns() : n.columns() - 1;
    for (std::uint32_t r = 0; r < n.rows(); ++r) {
      for (std::uint32_t c = 0; c < edges; ++c) {
        for (int i = 0; i <= 20; ++i) {
          const double u = i / 20.0;
          // Left patch at its v = 1 (its own spline pieces) against the right one at v = 0. Where a
          // knot lies on the edge the two pieces' B-spline weights are the same numbers in the same
          // order, so a C2 spline gives exactly equal values: the jumps come out 0, not merely small.
          jumps.add(n.evaluate(r, c, u, 1.0), n.evaluate(r, (c + 1) % n.columns(), u, 0.0));
        }
      }
    }
    std::printf("v-edges (%s): relative jumps S %.1e, S_v %.1e, S_vv %.1e (S_u %.1e, S_uu %.1e, S_uv %.1e)\n",
                s.closed_u ? "torus" : s.closed_v ? "tube" : "sheet", jumps.relative(0), jumps.relative(3),
                jumps.relative(4), jumps.relative(1), jumps.relative(2), jumps.relative(5));
    for (std::size_t i = 0; i < 6; ++i) EXPECT_LE(jumps.relative(i), 1e-13) << i;
  }
}

TEST(Network, PatchObjectsAgreeWithTheNetwork) {
  const Network n = build(sweptNetwork(sweptLayouts()[0], mixedRowShapes()));
  for (std::uint32_t r = 0; r < n.rows(); ++r) {
    Result<Patch> patch = n.patch(r, 2);
    ASSERT_TRUE(patch.ok());
    for (double u : {0.0, 0.4, 1.0}) {
      for (double v : {0.0, 0.7, 1.0}) {
        const PatchPoint a = patch->evaluate(u, v);
        const PatchPoint b = n.evaluate(r, 2, u, v);
        EXPECT_LT(glm::length(a.s - b.s), 1e-14);
        EXPECT_LT(glm::length(a.s_uu - b.s_uu), 1e-12);
        EXPECT_LT(glm::length(a.s_vv - b.s_vv), 1e-12);
      }
    }
  }
  EXPECT_EQ(n.patch(3, 0).status().code(), StatusCode::kOutOfRange);
}

// The thesis's Fig 4.1(b): (1, 3, 1) next to (0.1, 3, 0.1) in v.
NetworkDescription fig41b() {
  NetworkDescription d = sweptNetwork(sweptLayouts()[0], {{1, 3, 1}});
  d.shapes[2] = {0.1, 3.0, 0.1};
  return d;
}

TEST(Network, RefusesVPairingsThatCannotBeC2) {
  Result<Network> refused = Network::build(fig41b());
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.status().code(), StatusCode::kInvalidArgument);
  const std::string& message = refused.status().message();
  EXPECT_NE(message.find("patch (row 0, column 1) and patch (row 0, column 2)"), std::string::npos) << message;
  EXPECT_NE(message.find("eta/rho = 3 vs 30"), std::string::npos) << message;
  EXPECT_NE(message.find("erratum F9"), std::string::npos) << message;

  NetworkDescription warn = fig41b();
  warn.continuity = ContinuityPolicy::kWarn;
  std::vector<std::string> warnings;
  Result<Network> built = Network::build(warn, &warnings);
  ASSERT_TRUE(built.ok()) << built.status().toString();
  ASSERT_EQ(warnings.size(), 2u);  // columns 1|2 and 2|3
  // Not even C0 along the edge (F9): the two patches meet only at its ends.
  double gap = 0.0;
  for (int i = 1; i < 10; ++i) gap = std::max(gap, glm::length(built->evaluate(0, 1, i / 10.0, 1.0).s - built->evaluate(0, 2, i / 10.0, 0.0).s));
  std::printf("Fig 4.1(b) pairing: largest gap along the shared edge %.3g\n", gap);
  EXPECT_GT(gap, 1e-3);
  EXPECT_LT(glm::length(built->evaluate(0, 1, 0.0, 1.0).s - built->evaluate(0, 2, 0.0, 0.0).s), 1e-14);
}

TEST(Network, EqualRatiosShareCardinalFunctions) {
  NetworkDescription d = sweptNetwork(sweptLayouts()[0], {{1, 3, 1}});
  d.shapes[1] = {0.1, 0.3, 0.1};  // eta/rho = 2.9999999999999996
  d.shapes[3] = {-2, -6, -2};
  const Network n = build(d);
  EXPECT_EQ(n.cardinalIndex(0, 1), n.cardinalIndex(0, 0));
  EXPECT_EQ(n.cardinalIndex(0, 3), n.cardinalIndex(0, 0));
  EXPECT_EQ(n.cardinalCount(), n.rows());
}

TEST(Network, RejectsBadDescriptions) {
  const NetworkDescription good = sweptNetwork(sweptLayouts()[0], mixedRowShapes());
  auto expectInvalid = [](NetworkDescription d, const std::string& part) {
    Result<Network> n = Network::build(std::move(d));
    ASSERT_FALSE(n.ok()) << part;
    EXPECT_EQ(n.status().code(), StatusCode::kInvalidArgument) << n.status().toString();
    EXPECT_NE(n.status().message().find(part), std::string::npos) << n.status().message();
  };
  NetworkDescription d = good;
  d.curve_closed[3] = false;
  expectInvalid(d, "all closed");
  d = good;
  d.shapes.pop_back();
  expectInvalid(d, "11 shapes for 3 rows x 4 columns");
  d = good;
  d.boundaries[1].position = 999;
  expectInvalid(d, "boundary 'b1': position curve index 999");
  d = good;
  d.curve_names[1] = d.curve_names[0];
  expectInvalid(d, "defined twice");
  d = good;
  d.boundaries[0].source = DerivativeSource::kControlCurves;
  d.boundaries[0].side = ControlSide::kBefore;
  d.boundaries[0].u_lower = 0.6;
  d.boundaries[0].u_upper = 0.8;
  expectInvalid(d, "'before' the first boundary");
  d = good;  // b1 has controls after at (0.2, 0.4); b2 is given by curves: make b2 controls before at (0.3, 0.8)
  d.boundaries[2] = d.boundaries[1];
  d.boundaries[2].position = good.boundaries[2].position;
  d.boundaries[2].side = ControlSide::kBefore;
  d.boundaries[2].u_lower = 0.3;
  d.boundaries[2].u_upper = 0.8;
  expectInvalid(d, "need u3 <= u5");
  d = good;
  d.boundaries[1].u_upper = 1.0;
  expectInvalid(d, "0 < u2 < u3 < 1");
  d = good;
  d.shapes[5] = {0.0, 1.0, 1.0};
  Result<Network> degenerate = Network::build(d);
  EXPECT_EQ(degenerate.status().code(), StatusCode::kDegenerate);
  EXPECT_NE(degenerate.status().message().find("patch (row 1, column 1)"), std::string::npos);
  d = good;
  for (Ode6Shape& s : d.shapes) s = {1.0, 80.76291422570652, 0.0};
  EXPECT_EQ(Network::build(d).status().code(), StatusCode::kIllPosed);
}

TEST(Network, EditsReportTheChangedPatches) {
  Network n = build(sweptNetwork(sweptLayouts()[0], mixedRowShapes()));  // 3 rows x 4 columns, 4 boundaries
  Result<std::vector<std::uint32_t>> row = n.setRowShape(1, {1, 4, 2});
  ASSERT_TRUE(row.ok());
  EXPECT_EQ(*row, (std::vector<std::uint32_t>{4, 5, 6, 7}));
  // One patch alone would break C2 with its v-neighbours ...
  EXPECT_EQ(n.setPatchShape(1, 2, {1, 5, 2}).status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(n.description().shapes[6].eta, 4.0);
  // ... unless the ratios stay.
  Result<std::vector<std::uint32_t>> patch = n.setPatchShape(1, 2, {2, 8, 4});
  ASSERT_TRUE(patch.ok());
  EXPECT_EQ(*patch, (std::vector<std::uint32_t>{6}));
  // A boundary tangent: the rows on both sides of boundary 1.
  NetworkBoundary b = n.description().boundaries[1];
  b.u_upper = 0.45;
  Result<std::vector<std::uint32_t>> boundary = n.setBoundary(1, b);
  ASSERT_TRUE(boundary.ok());
  EXPECT_EQ(*boundary, (std::vector<std::uint32_t>{0, 1, 2, 3, 4, 5, 6, 7}));
  // The first boundary belongs to row 0 only.
  NetworkBoundary first = n.description().boundaries[0];
  first.w_first = 0.5;
  EXPECT_EQ(n.setBoundary(0, first)->size(), 4u);
  // A bad edit changes nothing.
  b.u_lower = 0.5;
  EXPECT_FALSE(n.setBoundary(1, b).ok());
  EXPECT_EQ(n.description().boundaries[1].u_lower, 0.2);
  // The last boundary's curve: row 2 only.
  const std::uint32_t last_curve = n.description().boundaries[3].position;
  std::vector<Vec3> points = n.description().curve_points[last_curve];
  points[0].x += 0.1;
  Result<std::vector<std::uint32_t>> curve = n.setCurvePoints(last_curve, points);
  ASSERT_TRUE(curve.ok());
  EXPECT_EQ(*curve, (std::vector<std::uint32_t>{8, 9, 10, 11}));
  points.pop_back();
  EXPECT_EQ(n.setCurvePoints(last_curve, points).status().code(), StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace odeskin
