// SPDX-License-Identifier: MIT
// Blending surfaces (MATH.md 2.1, 2.13): boundary data from callables, polylines and primary
// surfaces; the four constraints met on every trimline for every regime; the grid tessellation's
// vertex layout, faces and wrap; the thesis's examples and the three-plane corner blend.
#include "engine/surfaces/blending_surface.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <set>
#include <vector>

#include "engine/surfaces/blend_examples.hpp"
#include "engine/surfaces/corner_blend.hpp"
#include "engine/surfaces/hermite_blend.hpp"

namespace odeskin {
namespace {

constexpr double kPi = std::numbers::pi;

double distance(const Vec3& a, const Vec3& b) { return glm::length(a - b); }

// Largest |S(0,v) - C0|, |S_u(0,v) - C0bar|, |S(1,v) - C1|, |S_u(1,v) - C1bar| over v, divided by
// the size of the data involved (positions: max |C|; tangents: max |Cbar| + slope scale x max |C|).
double constraintError(const BlendingSurface& s, double slope_scale) {
  const VDomain& d = s.boundary().domain();
  double position = 0.0, tangent = 0.0, size = 0.0, tangent_size = 0.0;
  for (int j = 0; j <= 64; ++j) {
    const double v = d.v_begin + (d.v_end - d.v_begin) * j / 64.0;
    const TrimlineSample b = s.boundary().at(v);
    size = std::max({size, glm::length(b.c0), glm::length(b.c1)});
    tangent_size = std::max({tangent_size, glm::length(b.c0bar), glm::length(b.c1bar)});
    position = std::max({position, distance(s.at(0.0, v), b.c0), distance(s.at(1.0, v), b.c1)});
    tangent = std::max({tangent, distance(s.derivativeU(0.0, v), b.c0bar), distance(s.derivativeU(1.0, v), b.c1bar)});
  }
  return std::max(position / size, tangent / (tangent_size + slope_scale * size));
}

BoundaryData circleToEllipse() {
  Result<Trimline> a = trimlineFromFunctions([](double v) { return Vec3(std::cos(v), std::sin(v), 1.0); },
                                             [](double v) { return Vec3(0.3 * std::cos(v), 0.3 * std::sin(v), -1.0); });
  Result<Trimline> b = trimlineFromFunctions([](double v) { return Vec3(2.0 * std::cos(v), 1.5 * std::sin(v), -1.0); },
                                             [](double v) { return Vec3(std::cos(v), std::sin(v), -0.5); });
  return *BoundaryData::create(*a, *b);
}

TEST(BlendingSurface, MeetsTheFourConstraintsInEveryRegime) {
  const struct {
    double alpha, beta, gamma, slope_scale;
  } cases[] = {
      {1, -5, 4, 1},       {1, 3, 1, 1},         {1, 3, -4, 1},      {1, -4, 0, 1},     {1, 4, 0, 1},
      {1, 0, 0, 1},        {-2.5, 0, 0, 1},      {1, -2, 1, 1},      {1, 2, 1, 1},      {1, 1, 1, 1},
      {-1, -1, -1, 1},     {1, 1e-6, 1e-9, 1},   {1, -4e6, 0, 2000}, {1, 0, 1e8, 100},  {1, -2e4, 1e8, 100},
      {1, 2e4, 1e8, 100},  {1, -1e10, 1, 1e5},
  };
  const BoundaryData data = circleToEllipse();
  for (const auto& c : cases) {
    Result<BlendingSurface> s = BlendingSurface::create(data, c.alpha, c.beta, c.gamma);
    ASSERT_TRUE(s.ok()) << s.status().toString();
    EXPECT_LT(constraintError(*s, c.slope_scale), 1e-12) << c.alpha << " " << c.beta << " " << c.gamma;
  }
}

TEST(BlendingSurface, PropagatesParameterErrors) {
  Result<BlendingSurface> nan = BlendingSurface::create(circleToEllipse(), 1.0, std::nan(""), 1.0);
  ASSERT_FALSE(nan.ok());
  EXPECT_NE(nan.status().message().find("beta is NaN"), std::string::npos);
  EXPECT_EQ(BlendingSurface::create(circleToEllipse(), 0.0, 1.0, 1.0).status().code(), StatusCode::kDegenerate);
  EXPECT_EQ(BlendingSurface::create(circleToEllipse(), 1.0, 4 * kPi * kPi, 0.0).status().code(), StatusCode::kIllPosed);
  EXPECT_EQ(BlendingSurface::create(circleToEllipse(), CardinalFunction{}).status().code(),
            StatusCode::kInvalidArgument);
}

TEST(BlendGrid, VertexLayoutFacesAndWrap) {
  Result<BlendingSurface> s = BlendingSurface::create(circleToEllipse(), 1.0, 2.0, 1.0);
  ASSERT_TRUE(s.ok());
  const std::uint32_t U = 7, V = 12;
  Result<BlendGrid> g = tessellateBlend(*s, U, V);
  ASSERT_TRUE(g.ok()) << g.status().toString();
  ASSERT_EQ(g->positions.size(), std::size_t{U} * V);
  EXPECT_TRUE(g->wraps_v);
  for (std::uint32_t i = 0; i < U; ++i) {
    for (std::uint32_t j = 0; j < V; ++j) {
      const double u = i / double(U - 1), v = 2.0 * kPi * j / V;
      EXPECT_LT(distance(g->positions[i * V + j], s->at(u, v)), 1e-15) << i << " " << j;
    }
  }
  // (U - 1) x V quads: every v-step including the seam from column V-1 back to column 0.
  ASSERT_EQ(g->faces.faceCount(), std::size_t{U - 1} * V);
  std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
  for (std::size_t f = 0; f < g->faces.faceCount(); ++f) {
    ASSERT_EQ(g->faces.face_offsets[f + 1] - g->faces.face_offsets[f], 4u);
    const std::uint32_t* q = &g->faces.indices[g->faces.face_offsets[f]];
    const std::uint32_t i = static_cast<std::uint32_t>(f) / V, j = static_cast<std::uint32_t>(f) % V;
    EXPECT_EQ(q[0], i * V + j);
    EXPECT_EQ(q[1], (i + 1) * V + j);
    EXPECT_EQ(q[2], (i + 1) * V + (j + 1) % V);
    EXPECT_EQ(q[3], i * V + (j + 1) % V);
    for (int e = 0; e < 4; ++e) edges.insert({q[e], q[(e + 1) % 4]});
  }
  // Closed in v: every directed edge has its twin except the u = 0 and u = 1 boundary rows.
  std::size_t unmatched = 0;
  for (const auto& [a, b] : edges) unmatched += edges.count({b, a}) == 0;
  EXPECT_EQ(unmatched, 2u * V);
  // Outward orientation: S_u x S_v points away from the axis for this downward-flaring blend.
  const std::size_t row = V;  // vertices per row of u
  const Vec3 p0 = g->positions[2 * row], p1 = g->positions[3 * row], p2 = g->positions[3 * row + 1];
  const Vec3 n = glm::cross(p1 - p0, p2 - p1);
  EXPECT_GT(glm::dot(n, Vec3(p0.x, p0.y, 0.0)), 0.0);
}

TEST(BlendGrid, OpenDomainIncludesBothEnds) {
  CornerBlendOptions o;
  Result<CornerBlend> corner = makeCornerBlend(o);
  ASSERT_TRUE(corner.ok()) << corner.status().toString();
  Result<BlendGrid> g = tessellateBlend(corner->top_front, 3, 5);
  ASSERT_TRUE(g.ok());
  EXPECT_FALSE(g->wraps_v);
  EXPECT_EQ(g->faces.faceCount(), 2u * 4u);
  EXPECT_LT(distance(g->positions[4], corner->top_front.at(0.0, 1.0)), 1e-15);
  EXPECT_LT(distance(g->positions[2 * 5 + 4], Vec3(1.0, 1.0, 1.5)), 1e-12);  // S_TF(1, 1) = C1(1)
}

TEST(BlendGrid, RejectsBadResolutions) {
  Result<BlendingSurface> s = BlendingSurface::create(circleToEllipse(), 1.0, 2.0, 1.0);
  ASSERT_TRUE(s.ok());
  EXPECT_EQ(tessellateBlend(*s, 1, 10).status().code(), StatusCode::kOutOfRange);
  EXPECT_EQ(tessellateBlend(*s, 10, 2).status().code(), StatusCode::kOutOfRange);
  EXPECT_NE(tessellateBlend(*s, 10, 2).status().message().find("wraps"), std::string::npos);
  EXPECT_EQ(tessellateBlend(*s, 100000, 100000).status().code(), StatusCode::kOutOfRange);
  Result<Trimline> bad = trimlineFromFunctions([](double v) { return Vec3(v > 1.0 ? std::nan("") : 0.0, 0.0, 0.0); },
                                               [](double) { return Vec3(0.0); });
  Result<BlendingSurface> nan_surface = BlendingSurface::create(*BoundaryData::create(*bad, *bad), 1.0, 0.0, 0.0);
  ASSERT_TRUE(nan_surface.ok());
  Result<BlendGrid> g = tessellateBlend(*nan_surface, 4, 8);
  ASSERT_FALSE(g.ok());
  EXPECT_NE(g.status().message().find("not finite at (u, v)"), std::string::npos) << g.status().message();
}

TEST(BoundaryData, PolylinesInterpolateTheirSamplesAndConverge) {
  double coarse = 0.0;
  for (int n : {16, 64}) {
    std::vector<Vec3> curve, tangent;
    for (int j = 0; j < n; ++j) {
      const double v = 2.0 * kPi * j / n;
      curve.emplace_back(std::cos(v), 2.0 * std::sin(v), std::sin(3.0 * v));
      tangent.emplace_back(0.0, 0.0, -1.0 - 0.5 * std::cos(v));
    }
    Result<Trimline> t = trimlineFromPolylines(curve, tangent, VDomain{});
    ASSERT_TRUE(t.ok()) << t.status().toString();
    double worst = 0.0;
    for (int j = 0; j < n; ++j) {
      EXPECT_LT(distance(t->curve(2.0 * kPi * j / n), curve[static_cast<std::size_t>(j)]), 1e-14);
    }
    for (int i = 0; i <= 1000; ++i) {
      const double v = 2.0 * kPi * i / 1000.0;
      worst = std::max(worst, distance(t->curve(v), Vec3(std::cos(v), 2.0 * std::sin(v), std::sin(3.0 * v))));
      // Periodic: one period later is the same point.
      EXPECT_LT(distance(t->curve(v + 2.0 * kPi), t->curve(v)), 1e-12);
    }
    // C2 cubic interpolation errs like h^4 |f^(4)|: 16 samples -> 6.8e-3, 64 -> 2.0e-5 (4^4 = 256 apart).
    EXPECT_LT(worst, n == 16 ? 1e-2 : 4e-5) << n;
    if (n == 16) coarse = worst;
    if (n == 64) {
      EXPECT_GT(coarse / worst, 200.0);
    }
  }
  // Open polylines: a natural spline reproduces a straight line exactly and clamps outside.
  Result<Trimline> line = trimlineFromPolylines({Vec3(0.0), Vec3(1.0, 0.0, 0.0), Vec3(2.0, 0.0, 0.0)},
                                                {Vec3(0.0, 0.0, 1.0), Vec3(0.0, 0.0, 1.0), Vec3(0.0, 0.0, 1.0)},
                                                VDomain{0.0, 1.0, false});
  ASSERT_TRUE(line.ok());
  EXPECT_LT(distance(line->curve(0.3), Vec3(0.6, 0.0, 0.0)), 1e-14);
  EXPECT_LT(distance(line->curve(1.5), Vec3(2.0, 0.0, 0.0)), 1e-14);
}

TEST(BoundaryData, RejectsBadInput) {
  EXPECT_FALSE(trimlineFromFunctions({}, [](double) { return Vec3(0.0); }).ok());
  EXPECT_FALSE(trimlineFromPolylines({Vec3(0.0), Vec3(1.0)}, {Vec3(0.0), Vec3(1.0)}, VDomain{}).ok());  // 2 < 3
  EXPECT_FALSE(trimlineFromPolylines({Vec3(0.0), Vec3(1.0), Vec3(2.0)}, {Vec3(0.0)}, VDomain{}).ok());
  Result<Trimline> nan = trimlineFromPolylines({Vec3(0.0), Vec3(std::nan(""), 0, 0), Vec3(2.0)},
                                               {Vec3(0.0), Vec3(1.0), Vec3(2.0)}, VDomain{});
  ASSERT_FALSE(nan.ok());
  EXPECT_NE(nan.status().message().find("curve sample 1"), std::string::npos) << nan.status().message();
  EXPECT_FALSE(trimlineFromPolylines({Vec3(0.0), Vec3(1.0), Vec3(2.0)}, {Vec3(0.0), Vec3(1.0), Vec3(2.0)},
                                     VDomain{1.0, 1.0, true}).ok());
  EXPECT_FALSE(trimlineFromSurface({}, {}, 0.5).ok());
  Result<Trimline> t = trimlineFromFunctions([](double) { return Vec3(0.0); }, [](double) { return Vec3(0.0); });
  EXPECT_FALSE(BoundaryData::create(*t, Trimline{}, VDomain{}).ok());
  EXPECT_FALSE(BoundaryData::create(*t, *t, VDomain{0.0, std::numeric_limits<double>::infinity(), true}).ok());
}

// Eq 3.15's u = 0 data are the torus iso-line at 0.85 and -(2.45/0.45) times its derivative; the
// finite-difference tangent (no derivative passed) agrees to 1e-9.
TEST(BoundaryData, FromPrimarySurfaceReproducesTheTorusTrimline) {
  Result<BlendExample> e = blendExample("3.15");
  ASSERT_TRUE(e.ok());
  SurfaceFunction torus = [](double s, double v) {
    const double ring = 1.7 + 0.45 * std::cos(s);
    return Vec3(ring * std::cos(v), ring * std::sin(v), 0.45 * std::sin(s));
  };
  Result<Trimline> numeric = trimlineFromSurface(torus, {}, 0.85, -2.45 / 0.45);
  ASSERT_TRUE(numeric.ok());
  for (int j = 0; j < 16; ++j) {
    const double v = 2.0 * kPi * j / 16;
    const Vec3 printed_c0(1.7 + 0.45 * std::cos(0.85), 0.0, 0.0);
    const double ring = 1.7 + 0.45 * std::cos(0.85);
    EXPECT_LT(distance(e->boundary.at(v).c0, Vec3(ring * std::cos(v), ring * std::sin(v), 0.45 * std::sin(0.85))), 1e-15);
    const Vec3 printed_c0bar(2.45 * std::sin(0.85) * std::cos(v), 2.45 * std::sin(0.85) * std::sin(v), -2.45 * std::cos(0.85));
    EXPECT_LT(distance(e->boundary.at(v).c0bar, printed_c0bar), 1e-14);
    EXPECT_LT(distance(numeric->tangent(v), printed_c0bar), 1e-9);
    (void)printed_c0;
  }
}

TEST(BlendExamples, EveryExampleBuildsAndMeetsItsConstraints) {
  EXPECT_EQ(blendExampleIds(), (std::vector<std::string>{"3.15", "3.16", "3.17", "3.18"}));
  for (const std::string& id : blendExampleIds()) {
    Result<BlendExample> e = blendExample(id);
    ASSERT_TRUE(e.ok()) << id << ": " << e.status().toString();
    EXPECT_EQ(e->id, id);
    Result<BlendingSurface> s = BlendingSurface::create(e->boundary, e->thesis.alpha, e->thesis.beta, e->thesis.gamma);
    ASSERT_TRUE(s.ok()) << s.status().toString();
    EXPECT_LT(constraintError(*s, 1.0), 1e-12) << id;
    Result<BlendGrid> g = tessellateBlend(*s, 20, 40);
    ASSERT_TRUE(g.ok());
  }
  // Spot values of the printed data.
  EXPECT_LT(distance(blendExample("3.16")->boundary.at(0.0).c0, Vec3(1.013 * 0.96, 0.0, 0.95)), 1e-15);
  EXPECT_LT(distance(blendExample("3.17")->boundary.at(kPi / 2).c1, Vec3(0.0, 0.4 * std::sinh(1.4), -1.5 * std::cosh(1.4))),
            1e-15);
  EXPECT_LT(distance(blendExample("3.18")->boundary.at(0.0).c1bar, Vec3(1.2, 0.0, -1.8)), 1e-15);
  Result<BlendExample> garbled = blendExample("3.14");
  ASSERT_FALSE(garbled.ok());
  EXPECT_NE(garbled.status().message().find("C14"), std::string::npos);
  Result<BlendExample> unknown = blendExample("3.99");
  ASSERT_FALSE(unknown.ok());
  EXPECT_NE(unknown.status().message().find("unknown blend example '3.99'"), std::string::npos);
  EXPECT_EQ(figure35Parameters().size(), 4u);
  EXPECT_EQ(figure37Parameters().size(), 3u);
}

// MATH.md 2.9: the Hermite blend of Eq 3.19 is the ODE blend with beta = gamma = 0.
TEST(BlendExamples, HermiteBlendIsTheOdeBlendWithoutBetaAndGamma) {
  const BoundaryData data = blendExample("3.18")->boundary;
  Result<BlendingSurface> hermite = BlendingSurface::create(data, hermiteCardinals);
  Result<BlendingSurface> ode = BlendingSurface::create(data, 3.0, 0.0, 0.0);
  ASSERT_TRUE(hermite.ok() && ode.ok());
  for (int i = 0; i <= 10; ++i) {
    for (int j = 0; j < 8; ++j) {
      const double u = i / 10.0, v = 2.0 * kPi * j / 8;
      EXPECT_LT(distance(hermite->at(u, v), ode->at(u, v)), 1e-14);
    }
  }
  const std::array<double, 4> h = hermiteBasis(0.25);
  EXPECT_DOUBLE_EQ(h[0], 0.75 * 0.75 * 1.5);
  EXPECT_DOUBLE_EQ(h[2], -0.0625 * 0.75);
}

TEST(CornerBlend, BlendsMeetAtTheCornerAndThePatchClosesTheHole) {
  Result<CornerBlend> c = makeCornerBlend();
  ASSERT_TRUE(c.ok()) << c.status().toString();
  // The corner stated in the text (C16): S_TF(0, 1) = S_TS(0, 0); and TF, TS, FS meet pairwise.
  EXPECT_LT(distance(c->top_front.at(0.0, 1.0), c->top_side.at(0.0, 0.0)), 1e-15);
  EXPECT_LT(distance(c->top_front.at(1.0, 1.0), c->front_side.at(0.0, 1.0)), 1e-15);
  EXPECT_LT(distance(c->top_side.at(1.0, 0.0), c->front_side.at(1.0, 1.0)), 1e-15);
  for (const BlendingSurface* s : {&c->top_front, &c->top_side, &c->front_side, &c->patch}) {
    EXPECT_LT(constraintError(*s, 1.0), 1e-12);
  }
  // The patch: its u = 0 row is the corner point, its u = 1 row is FS's v = 1 edge, and its
  // v = 0 / v = 1 columns start and end where TF's v = 1 and TS's v = 0 edges do.
  for (int i = 0; i <= 10; ++i) {
    const double v = i / 10.0;
    EXPECT_LT(distance(c->patch.at(0.0, v), c->top_front.at(0.0, 1.0)), 1e-15);
    EXPECT_LT(distance(c->patch.at(1.0, v), c->front_side.at(v, 1.0)), 1e-14);
  }
  double gap = 0.0;
  for (int i = 0; i <= 20; ++i) {
    const double u = i / 20.0;
    gap = std::max({gap, distance(c->patch.at(u, 0.0), c->top_front.at(u, 1.0)),
                    distance(c->patch.at(u, 1.0), c->top_side.at(u, 0.0))});
  }
  EXPECT_GT(gap, 1e-3);  // s = -1: the end tangents are twice TF's and TS's, the edges bulge apart
  // With s = -1/2 the patch's end tangents equal TF's and TS's, so its side edges coincide with theirs.
  CornerBlendOptions half;
  half.bottom_tangent_scale = -0.5;
  Result<CornerBlend> h = makeCornerBlend(half);
  ASSERT_TRUE(h.ok());
  for (int i = 0; i <= 20; ++i) {
    const double u = i / 20.0;
    EXPECT_LT(distance(h->patch.at(u, 0.0), h->top_front.at(u, 1.0)), 1e-12) << u;
    EXPECT_LT(distance(h->patch.at(u, 1.0), h->top_side.at(u, 0.0)), 1e-12) << u;
  }
}

TEST(CornerBlend, RejectsBadDimensions) {
  CornerBlendOptions o;
  o.dimensions.r = 0.0;
  Result<CornerBlend> c = makeCornerBlend(o);
  ASSERT_FALSE(c.ok());
  EXPECT_NE(c.status().message().find("r must be positive"), std::string::npos);
  o = {};
  o.dimensions.ly = std::nan("");
  EXPECT_NE(makeCornerBlend(o).status().message().find("ly is not finite"), std::string::npos);
  o = {};
  o.parameters.alpha = 0.0;
  EXPECT_EQ(makeCornerBlend(o).status().code(), StatusCode::kDegenerate);
}

}  // namespace
}  // namespace odeskin
