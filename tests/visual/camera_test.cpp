// SPDX-License-Identifier: MIT
// The picture camera: the view angles, Vulkan's projection conventions, and framing that keeps
// every point inside the image with the margin, tightly (a point touches the margin) and centred.
#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/visual/camera.hpp"

namespace odeskin::visual {
namespace {

std::vector<Vec3> randomCloud(unsigned seed, const Vec3& scale, const Vec3& offset) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Vec3> points(500);
  for (Vec3& p : points) p = offset + scale * Vec3(u(rng), u(rng), u(rng));
  return points;
}

// Extremes of the points' projections in normalised device coordinates.
struct NdcExtent {
  double x_lo = 1e300, x_hi = -1e300, y_lo = 1e300, y_hi = -1e300, z_lo = 1e300, z_hi = -1e300;
};

NdcExtent ndcExtent(const Camera& camera, const std::vector<Vec3>& points) {
  NdcExtent e;
  for (const Vec3& p : points) {
    const Vec3 px = projectToPixel(camera, p, 2.0, 2.0);  // a 2 x 2 image: pixels = ndc + 1
    e.x_lo = std::min(e.x_lo, px.x - 1.0);
    e.x_hi = std::max(e.x_hi, px.x - 1.0);
    e.y_lo = std::min(e.y_lo, px.y - 1.0);
    e.y_hi = std::max(e.y_hi, px.y - 1.0);
    e.z_lo = std::min(e.z_lo, px.z);
    e.z_hi = std::max(e.z_hi, px.z);
  }
  return e;
}

TEST(Camera, ViewDirectionFollowsAzimuthAndElevation) {
  ViewSpec view;
  view.azimuth_deg = 0.0;
  view.elevation_deg = 0.0;
  const Vec3 front = viewDirection(view);
  EXPECT_NEAR(glm::length(front - Vec3(0, 0, 1)), 0.0, 1e-12);
  view.azimuth_deg = 90.0;  // right-handed about +y: +z turns to +x
  EXPECT_NEAR(glm::length(viewDirection(view) - Vec3(1, 0, 0)), 0.0, 1e-12);
  view.azimuth_deg = 0.0;
  view.elevation_deg = 30.0;
  EXPECT_NEAR(viewDirection(view).y, 0.5, 1e-12);
  view.up = Vec3(0, 0, 1);  // z up: azimuth 0 looks from +x
  view.elevation_deg = 0.0;
  EXPECT_NEAR(glm::length(viewDirection(view) - Vec3(1, 0, 0)), 0.0, 1e-12);
}

// Azimuths are angles, so any finite one is a view: 1e308 degrees once overflowed to inf radians
// and left the camera NaN ("the camera's far plane must be positive and finite").
TEST(Camera, HugeAzimuthsAreWholeTurnsPlusTheRest) {
  ViewSpec view;
  view.elevation_deg = 10.0;
  const double huge = 1e308;
  view.azimuth_deg = std::fmod(huge, 360.0);
  const Vec3 reduced = viewDirection(view);
  for (const double azimuth : {huge, -huge, 720.0 + 45.0}) {
    view.azimuth_deg = azimuth;
    const Vec3 d = viewDirection(view);
    ASSERT_TRUE(std::isfinite(d.x) && std::isfinite(d.y) && std::isfinite(d.z)) << azimuth;
    ASSERT_TRUE(validateViewSpec(view).ok()) << azimuth;
    const std::vector<Vec3> points = randomCloud(3, Vec3(1.0, 2.0, 0.5), Vec3(0.0));
    EXPECT_TRUE(framePoints(points, 1.0, view).ok()) << azimuth;
    EXPECT_TRUE(turntableCameras(points, 1.0, view, std::vector<double>{0.0, 180.0}).ok()) << azimuth;
  }
  view.azimuth_deg = huge;
  EXPECT_NEAR(glm::length(viewDirection(view) - reduced), 0.0, 1e-12);
  view.azimuth_deg = 720.0 + 45.0;
  const Vec3 d = viewDirection(view);
  view.azimuth_deg = 45.0;
  EXPECT_NEAR(glm::length(viewDirection(view) - d), 0.0, 1e-12);
}

TEST(Camera, OutOfRangeSettingsAreNamedInShortNumbers) {
  ViewSpec view;
  view.elevation_deg = 1e308;
  EXPECT_EQ(validateViewSpec(view).message(), "view: elevation 1e+308 must lie in (-89, 89) degrees");
  view.elevation_deg = 0.0;
  view.fov_y_deg = -1e308;
  EXPECT_EQ(validateViewSpec(view).message(), "view: field of view -1e+308 must lie in (1, 170) degrees");
}

TEST(Camera, ProjectionIsVulkans) {
  Camera camera;
  camera.near = 0.5;
  camera.far = 4.0;
  camera.fov_y_rad = std::acos(-1.0) / 2.0;  // 90 degrees: y_ndc = -y / -z
  camera.aspect = 2.0;
  // View space: in front of the camera is -z.
  auto ndc = [&](const Vec3& v) {
    const glm::dvec4 c = camera.projection() * glm::dvec4(v, 1.0);
    return Vec3(c) / c.w;
  };
  EXPECT_NEAR(ndc({0, 0, -0.5}).z, 0.0, 1e-12);
  EXPECT_NEAR(ndc({0, 0, -4.0}).z, 1.0, 1e-12);
  EXPECT_NEAR(ndc({0, 1, -1}).y, -1.0, 1e-12);  // up in the world is up in the picture (y down)
  EXPECT_NEAR(ndc({2, 0, -1}).x, 1.0, 1e-12);   // aspect 2: x reaches the edge at twice y's angle
}

TEST(Camera, FramePointsIsTightCentredAndInside) {
  for (unsigned seed = 1; seed <= 4; ++seed) {
    const std::vector<Vec3> points = randomCloud(seed, Vec3(0.3, 1.0, 2.0), Vec3(5.0, -2.0, 1.0));
    for (double aspect : {0.5, 1.0, 2.5}) {
      ViewSpec view;
      view.azimuth_deg = 20.0 * seed;
      view.elevation_deg = 10.0 * seed - 15.0;
      Result<Camera> camera = framePoints(points, aspect, view);
      ASSERT_TRUE(camera.ok()) << camera.status().toString();
      const NdcExtent e = ndcExtent(*camera, points);
      const double limit = 1.0 - view.margin;
      EXPECT_LE(std::max({-e.x_lo, e.x_hi, -e.y_lo, e.y_hi}), limit + 1e-9);
      // Tight and centred: on the axis that decides the distance the points touch both margins.
      auto touches = [limit](double lo, double hi) { return std::abs(hi - limit) < 1e-6 && std::abs(lo + limit) < 1e-6; };
      EXPECT_TRUE(touches(e.x_lo, e.x_hi) || touches(e.y_lo, e.y_hi))
          << "x [" << e.x_lo << ", " << e.x_hi << "] y [" << e.y_lo << ", " << e.y_hi << "]";
      // Every point lies between the near and far planes.
      EXPECT_GT(e.z_lo, 0.0);
      EXPECT_LT(e.z_hi, 1.0);
    }
  }
}

TEST(Camera, TurntableKeepsTheDistanceAndFramesEveryAngle) {
  const std::vector<Vec3> points = randomCloud(7, Vec3(2.0, 0.5, 0.4), Vec3(0.0, 1.0, 0.0));
  std::vector<double> azimuths;
  azimuths.reserve(12);
  for (int f = 0; f < 12; ++f) azimuths.push_back(30.0 * f);
  Result<std::vector<Camera>> cameras = turntableCameras(points, 4.0 / 3.0, ViewSpec{}, azimuths);
  ASSERT_TRUE(cameras.ok()) << cameras.status().toString();
  ASSERT_EQ(cameras->size(), azimuths.size());
  const Vec3 centre = boundsOf(points).centre();
  const double distance = glm::length(cameras->front().position() - centre);
  for (const Camera& camera : *cameras) {
    EXPECT_NEAR(glm::length(camera.position() - centre), distance, 1e-9 * distance);
    // The turntable axis (the box centre) stays in the middle of the picture.
    const Vec3 middle = projectToPixel(camera, centre, 2.0, 2.0);
    EXPECT_NEAR(middle.x, 1.0, 1e-9);
    EXPECT_NEAR(middle.y, 1.0, 1e-9);
    const NdcExtent e = ndcExtent(camera, points);
    EXPECT_LE(std::max({-e.x_lo, e.x_hi, -e.y_lo, e.y_hi}), 1.0 - ViewSpec{}.margin + 1e-9);
  }
}

TEST(Camera, RejectsWhatCannotBeFramed) {
  const std::vector<Vec3> points{{0, 0, 0}, {1, 1, 1}};
  EXPECT_EQ(framePoints({}, 1.0, ViewSpec{}).status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(framePoints(points, 0.0, ViewSpec{}).status().code(), StatusCode::kInvalidArgument);
  ViewSpec view;
  view.elevation_deg = 90.0;
  EXPECT_EQ(framePoints(points, 1.0, view).status().code(), StatusCode::kInvalidArgument);
  view = ViewSpec{};
  view.fov_y_deg = 0.0;
  EXPECT_EQ(framePoints(points, 1.0, view).status().code(), StatusCode::kInvalidArgument);
  view = ViewSpec{};
  view.up = Vec3(0, 2, 0);
  EXPECT_EQ(framePoints(points, 1.0, view).status().code(), StatusCode::kInvalidArgument);
  view = ViewSpec{};
  view.azimuth_deg = std::nan("");
  EXPECT_EQ(framePoints(points, 1.0, view).status().code(), StatusCode::kInvalidArgument);
  // Points that are not finite, or whose squared distances overflow, give no camera (it would be
  // at infinity, and the picture empty).
  const std::vector<Vec3> nan{{0, 0, 0}, {1, std::nan(""), 1}};
  EXPECT_EQ(framePoints(nan, 1.0, ViewSpec{}).status().message(), "view: vertex 1 is not finite");
  const std::vector<Vec3> huge{{0, 0, 0}, {1e200, 1e200, 1e200}};
  const double turns[] = {0.0, 90.0};
  for (const Status& refused : {framePoints(huge, 1.0, ViewSpec{}).status(), turntableCameras(huge, 1.0, ViewSpec{}, turns).status()}) {
    EXPECT_EQ(refused.code(), StatusCode::kInvalidArgument);
    EXPECT_NE(refused.message().find("view: the mesh is too large for double-precision distances"), std::string::npos)
        << refused.message();
  }
  // One point repeated is framed as a unit box around it: it lands near the middle.
  const std::vector<Vec3> same(3, Vec3(2.0, 3.0, 4.0));
  Result<Camera> camera = framePoints(same, 1.0, ViewSpec{});
  ASSERT_TRUE(camera.ok());
  const Vec3 p = projectToPixel(*camera, same.front(), 100.0, 100.0);
  EXPECT_NEAR(p.x, 50.0, 15.0);
  EXPECT_NEAR(p.y, 50.0, 15.0);
  EXPECT_GT(p.z, 0.0);
  EXPECT_LT(p.z, 1.0);
}

}  // namespace
}  // namespace odeskin::visual
