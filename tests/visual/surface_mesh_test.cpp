// SPDX-License-Identifier: MIT
// Mesh preparation for drawing: fan triangulation, area-weighted normals, per-vertex errors over
// the reference's longest box side (MATH.md 6.1), curve segments as lerps of the (deformed) edge ends.
#include <cmath>

#include <gtest/gtest.h>

#include "engine/visual/curve_lines.hpp"
#include "engine/visual/surface_mesh.hpp"
#include "engine/visual/vertex_error.hpp"
#include "engine/visual/view_geometry.hpp"

namespace odeskin::visual {
namespace {

FaceList faces(std::initializer_list<std::initializer_list<std::uint32_t>> polygons) {
  FaceList f;
  for (const auto& polygon : polygons) {
    f.indices.insert(f.indices.end(), polygon.begin(), polygon.end());
    f.face_offsets.push_back(static_cast<std::uint32_t>(f.indices.size()));
  }
  return f;
}

TEST(SurfaceMesh, PolygonsBecomeFans) {
  const FaceList f = faces({{0, 1, 2, 3, 4}, {4, 3, 5}});
  Result<std::vector<std::uint32_t>> t = triangulateFaces(f, 6);
  ASSERT_TRUE(t.ok());
  EXPECT_EQ(*t, (std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3, 0, 3, 4, 4, 3, 5}));
  EXPECT_EQ(triangulateFaces(f, 5).status().code(), StatusCode::kInvalidArgument);  // vertex 5 of 5
  EXPECT_NE(triangulateFaces(faces({{0, 1}}), 3).status().message().find("face 0"), std::string::npos);
  FaceList broken = f;
  broken.face_offsets.back() = 99;
  EXPECT_EQ(triangulateFaces(broken, 6).status().code(), StatusCode::kInvalidArgument);
}

TEST(SurfaceMesh, NormalsAreAreaWeightedAndUnit) {
  // A unit square in z = 0 (counter-clockwise seen from +z) and a thin sliver folded up at one edge.
  const std::vector<Vec3> p{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0, 0.01}};
  const std::vector<Vec3> n = vertexNormals(p, faces({{0, 1, 2, 3}, {1, 0, 4}}));
  EXPECT_NEAR(glm::length(n[2] - Vec3(0, 0, 1)), 0.0, 1e-12);
  // Vertex 0 sees the square (area 1) and the sliver (area 0.0025): the square dominates.
  EXPECT_GT(n[0].z, 0.99);
  EXPECT_NEAR(glm::length(n[0]), 1.0, 1e-12);
  // A vertex in no face gets +z rather than a NaN.
  const std::vector<Vec3> lonely = vertexNormals(std::vector<Vec3>{{0, 0, 0}}, FaceList{});
  EXPECT_EQ(lonely[0], Vec3(0, 0, 1));
}

TEST(SurfaceMesh, NormalsDoNotDependOnSizeOrPlace) {
  // A square tilted about x. Far from the origin (1e9 times its size), products of absolute
  // positions cancel to noise; at 1e-150 across, the area vector's squared length underflows.
  const std::vector<Vec3> square{{0, 0, 0}, {1, 0, 0}, {1, 0.6, 0.8}, {0, 0.6, 0.8}};
  const Vec3 expected(0.0, -0.8, 0.6);
  for (const auto& [scale, offset] : {std::pair{1.0, Vec3(1e9, -2e9, 3e9)}, std::pair{1e-150, Vec3(0.0)},
                                      std::pair{1e150, Vec3(0.0)}}) {
    std::vector<Vec3> p(square.size());
    for (std::size_t i = 0; i < square.size(); ++i) p[i] = scale * square[i] + offset;
    for (const Vec3& n : vertexNormals(p, faces({{0, 1, 2, 3}}))) {
      EXPECT_LT(glm::length(n - expected), 1e-6) << scale << ": " << n.x << " " << n.y << " " << n.z;
    }
  }
}

TEST(VertexError, IsDistanceOverTheLongestBoxSide) {
  const std::vector<Vec3> ref{{0, 0, 0}, {5, 4, 0}};  // longest side 5 (the diagonal would be 6.4)
  const std::vector<Vec3> p{{0, 0, 1}, {5, 4, 0}};
  Result<std::vector<double>> e = relativeVertexErrors(p, ref);
  ASSERT_TRUE(e.ok());
  EXPECT_DOUBLE_EQ((*e)[0], 0.2);
  EXPECT_DOUBLE_EQ((*e)[1], 0.0);
  const Result<std::vector<double>> mismatch = relativeVertexErrors(std::vector<Vec3>(3), ref);
  EXPECT_EQ(mismatch.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(mismatch.status().message().find("3 vertices but the reference has 2"), std::string::npos);
  EXPECT_EQ(relativeVertexErrors(std::vector<Vec3>(2), std::vector<Vec3>(2)).status().code(),
            StatusCode::kInvalidArgument);
}

// Coordinates far beyond 1e154, whose squared distances overflowed to an error of "inf", and far
// below 1e-154, whose squares underflowed to 0: the errors are the same as at unit scale.
TEST(VertexError, HugeAndTinyCoordinatesKeepTheirRelativeErrors) {
  for (const double scale : {1e200, 1e-200, 1.5e308}) {
    const std::vector<Vec3> ref{{scale, 0, 0}, {-scale, 0, 0}, {0, 1e-300, 0}};
    const std::vector<Vec3> p{{0, 0, 0}, {scale, 0, 0}, {0, 1e-300, 0}};
    Result<std::vector<double>> e = relativeVertexErrors(p, ref);
    ASSERT_TRUE(e.ok()) << e.status().toString();
    EXPECT_DOUBLE_EQ((*e)[0], 0.5) << scale;
    EXPECT_DOUBLE_EQ((*e)[1], 1.0) << scale;
    EXPECT_EQ((*e)[2], 0.0) << scale;
  }
  // An error beyond double's range is an error, not "inf"; so is a vertex that is not finite.
  const std::vector<Vec3> tiny{{0, 0, 0}, {1e-300, 0, 0}};
  const std::vector<Vec3> far{{1e300, 0, 0}, {1e-300, 0, 0}};
  const Result<std::vector<double>> beyond = relativeVertexErrors(far, tiny);
  EXPECT_EQ(beyond.status().code(), StatusCode::kOutOfRange);
  EXPECT_NE(beyond.status().message().find("vertex 0 is more than"), std::string::npos) << beyond.status().message();
  const std::vector<Vec3> nan{{std::nan(""), 0, 0}, {1, 0, 0}};
  EXPECT_EQ(relativeVertexErrors(nan, tiny).status().code(), StatusCode::kInvalidArgument);
}

TEST(CurveLines, SegmentsFollowTheDeformedEdges) {
  IsoCurve closed;
  closed.points = {{0, 1, 0.5}, {1, 2, 0.25}, {2, 2, 0.0}};
  closed.part = 4;
  IsoCurve open = closed;
  open.closed = false;
  open.part = 7;
  std::vector<Vec3> p{{0, 0, 0}, {2, 0, 0}, {2, 4, 0}};
  Result<CurveSegments> s = curveSegments(std::vector<IsoCurve>{closed, open}, p);
  ASSERT_TRUE(s.ok());
  ASSERT_EQ(s->endpoints.size(), 2u * (3 + 2));
  EXPECT_EQ(s->endpoints[0], Vec3(1, 0, 0));
  EXPECT_EQ(s->endpoints[1], Vec3(2, 1, 0));
  EXPECT_EQ(s->endpoints[5], Vec3(1, 0, 0));  // the closing segment returns to the start
  EXPECT_EQ(s->curve_of_segment, (std::vector<std::uint32_t>{0, 0, 0, 1, 1}));
  EXPECT_EQ(s->part_of_segment, (std::vector<std::uint32_t>{4, 4, 4, 7, 7}));
  // Deforming the mesh moves the curve with it: same edge ratios.
  p[1] = {2, 0, 2};
  EXPECT_EQ(curveSegments(std::vector<IsoCurve>{closed}, p)->endpoints[0], Vec3(1, 0, 1));
  closed.points[1].b = 9;
  const Result<CurveSegments> bad = curveSegments(std::vector<IsoCurve>{closed}, p);
  EXPECT_NE(bad.status().message().find("curve 0 point 1 uses vertex 9"), std::string::npos) << bad.status().message();
}

TEST(ViewGeometry, AppliesTheViewInDoublePrecision) {
  const glm::dmat4 view = glm::dmat4(glm::dmat3(0, 1, 0, -1, 0, 0, 0, 0, 1)) *
                          glm::dmat4(1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 1, 2, 3, 1);  // translate, then turn 90 about z
  const std::vector<Vec3> p{{1, 0, 0}};
  const std::vector<Vec3> n{{1, 0, 0}};
  const std::vector<double> v{0.25};
  const std::vector<SurfaceVertex> out = surfaceVertices(view, p, n, v);
  EXPECT_FLOAT_EQ(out[0].position[0], -2.0f);  // (2, 2, 3) turned: (-2, 2, 3)
  EXPECT_FLOAT_EQ(out[0].position[1], 2.0f);
  EXPECT_FLOAT_EQ(out[0].normal[1], 1.0f);     // the normal turns but does not move
  EXPECT_FLOAT_EQ(out[0].normal[0], 0.0f);
  EXPECT_FLOAT_EQ(out[0].value, 0.25f);
  EXPECT_FLOAT_EQ(surfaceVertices(view, p, n)[0].value, 0.0f);
  EXPECT_EQ(viewPoints(view, p)[0], glm::vec3(-2.0f, 2.0f, 3.0f));
  // A uniform scale in the view (the renderer's, to fit float's range) leaves normals unit length.
  const glm::dmat4 scaled = glm::dmat4(glm::dmat3(1e-120)) * view;
  EXPECT_FLOAT_EQ(surfaceVertices(scaled, p, n)[0].normal[1], 1.0f);
}

}  // namespace
}  // namespace odeskin::visual
