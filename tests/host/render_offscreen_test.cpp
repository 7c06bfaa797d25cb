// SPDX-License-Identifier: MIT
// The offscreen renderer against its CPU references, under the validation layer: the picture has
// the requested size; the silhouette is where a CPU rasterisation of the projected triangles puts
// it; a flat face has the colour shadeColour() predicts, front or back; a heat ramp follows
// heatColour() with its hue falling along the ramp; curves show over the surface and hide behind it.
#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "engine/io/obj_reader.hpp"
#include "engine/visual/camera.hpp"
#include "engine/visual/render_shading.hpp"
#include "engine/visual/surface_mesh.hpp"
#include "engine/visual/view_geometry.hpp"
#include "host/gpu_test_support.hpp"
#include "host/render/offscreen_renderer.hpp"
#include "visual/render_colour.hpp"

namespace odeskin::vk {
namespace {

using visual::Camera;
using visual::Image;
using visual::Rgba8;
using visual::SurfaceVertex;

constexpr glm::vec3 kGrey{0.7f, 0.72f, 0.75f};

// Camera at the origin looking down -z: geometry is given in view space directly.
Camera viewSpaceCamera(double aspect) {
  Camera camera;
  camera.fov_y_rad = std::acos(-1.0) / 3.0;  // 60 degrees
  camera.aspect = aspect;
  camera.near = 1.0;
  camera.far = 200.0;
  return camera;
}

// A w x h grid of quads spanning corner + [0, 1] u + [0, 1] v, counter-clockwise seen from
// u x v; every vertex gets `normal` and value = its u coordinate.
struct Grid {
  std::vector<Vec3> positions;
  std::vector<std::uint32_t> triangles;
};

Grid grid(const Vec3& corner, const Vec3& u, const Vec3& v, std::uint32_t nu, std::uint32_t nv, bool reversed = false) {
  Grid g;
  for (std::uint32_t j = 0; j <= nv; ++j) {
    for (std::uint32_t i = 0; i <= nu; ++i) g.positions.push_back(corner + (double(i) / nu) * u + (double(j) / nv) * v);
  }
  for (std::uint32_t j = 0; j < nv; ++j) {
    for (std::uint32_t i = 0; i < nu; ++i) {
      const std::uint32_t a = j * (nu + 1) + i;
      const std::uint32_t b = a + 1;
      const std::uint32_t c = a + nu + 2;
      const std::uint32_t d = a + nu + 1;
      for (std::uint32_t index : reversed ? std::vector<std::uint32_t>{a, c, b, a, d, c}
                                          : std::vector<std::uint32_t>{a, b, c, a, c, d}) {
        g.triangles.push_back(index);
      }
    }
  }
  return g;
}

std::vector<SurfaceVertex> vertices(const Grid& g, const Vec3& normal, const std::vector<double>& values = {}) {
  return visual::surfaceVertices(glm::dmat4(1.0), g.positions, std::vector<Vec3>(g.positions.size(), normal), values);
}

Rgba8 expectedShade(const Vec3& n, const glm::vec3& base) {
  return visual::toRgba8(visual::shader::shadeColour(glm::normalize(glm::vec3(n)), base));
}

class RenderOffscreen : public testing::GpuTest {
 protected:
  OffscreenRenderer renderer(std::uint32_t w, std::uint32_t h, std::uint32_t samples = 4) {
    Result<OffscreenRenderer> r = OffscreenRenderer::create(device(), {w, h, samples});
    EXPECT_TRUE(r.ok()) << r.status().toString();
    return r.ok() ? std::move(r).value() : OffscreenRenderer{};
  }
  static Image draw(OffscreenRenderer& r, const FrameDraw& frame) {
    Result<Image> image = r.render(frame);
    EXPECT_TRUE(image.ok()) << image.status().toString();
    return image.ok() ? std::move(image).value() : Image{};
  }
};

TEST_F(RenderOffscreen, PictureHasTheRequestedSizeAndAClearBackground) {
  OffscreenRenderer r = renderer(97, 61);
  EXPECT_EQ(r.width(), 97u);
  EXPECT_EQ(r.height(), 61u);
  EXPECT_GE(r.samples(), 1u);
  const Image image = draw(r, FrameDraw{});
  EXPECT_EQ(image.width, 97u);
  EXPECT_EQ(image.height, 61u);
  EXPECT_TRUE(std::all_of(image.pixels.begin(), image.pixels.end(), [](Rgba8 p) { return p == Rgba8{}; }));
  EXPECT_EQ(OffscreenRenderer::create(device(), {0, 10, 4}).status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(OffscreenRenderer::create(device(), {1u << 20, 10, 4}).status().code(), StatusCode::kInvalidArgument);
}

// Pixel centres a CPU rasterisation of the projected triangles covers (either winding).
std::vector<bool> cpuCoverage(const Camera& camera, const std::vector<Vec3>& positions,
                              const std::vector<std::uint32_t>& triangles, std::uint32_t w, std::uint32_t h) {
  std::vector<Vec3> px;
  px.reserve(positions.size());
  for (const Vec3& p : positions) px.push_back(visual::projectToPixel(camera, p, w, h));
  std::vector<bool> covered(std::size_t(w) * h, false);
  for (std::size_t t = 0; t < triangles.size(); t += 3) {
    const Vec3 a = px[triangles[t]], b = px[triangles[t + 1]], c = px[triangles[t + 2]];
    const double area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    if (area == 0.0) continue;
    const auto x0 = static_cast<std::int64_t>(std::max(0.0, std::floor(std::min({a.x, b.x, c.x}))));
    const auto x1 = static_cast<std::int64_t>(std::min(double(w - 1), std::ceil(std::max({a.x, b.x, c.x}))));
    const auto y0 = static_cast<std::int64_t>(std::max(0.0, std::floor(std::min({a.y, b.y, c.y}))));
    const auto y1 = static_cast<std::int64_t>(std::min(double(h - 1), std::ceil(std::max({a.y, b.y, c.y}))));
    for (std::int64_t y = y0; y <= y1; ++y) {
      for (std::int64_t x = x0; x <= x1; ++x) {
        const double cx = double(x) + 0.5, cy = double(y) + 0.5;
        const double e0 = (b.x - a.x) * (cy - a.y) - (b.y - a.y) * (cx - a.x);
        const double e1 = (c.x - b.x) * (cy - b.y) - (c.y - b.y) * (cx - b.x);
        const double e2 = (a.x - c.x) * (cy - c.y) - (a.y - c.y) * (cx - c.x);
        const bool inside = area > 0 ? (e0 >= 0 && e1 >= 0 && e2 >= 0) : (e0 <= 0 && e1 <= 0 && e2 <= 0);
        if (inside) covered[std::size_t(y) * w + std::size_t(x)] = true;
      }
    }
  }
  return covered;
}

TEST_F(RenderOffscreen, SilhouetteIsWhereTheProjectedMeshIs) {
  Result<ObjMesh> mesh = readObj(std::string(ODESKIN_DATA_DIR) + "/cylinder/poses-1/cylinder-3.obj");
  ASSERT_TRUE(mesh.ok()) << mesh.status().toString();
  constexpr std::uint32_t kW = 160, kH = 120;
  visual::ViewSpec view;
  view.azimuth_deg = 35.0;
  view.elevation_deg = 25.0;
  Result<Camera> camera = visual::framePoints(mesh->positions, double(kW) / kH, view);
  ASSERT_TRUE(camera.ok());
  Result<std::vector<std::uint32_t>> triangles = visual::triangulateFaces(mesh->faces, mesh->positions.size());
  ASSERT_TRUE(triangles.ok());
  const std::vector<SurfaceVertex> v = visual::surfaceVertices(
      camera->view, mesh->positions, visual::vertexNormals(mesh->positions, mesh->faces));
  FrameDraw frame;
  frame.projection = glm::mat4(camera->projection());
  frame.surfaces.push_back({v, *triangles, kGrey});
  OffscreenRenderer r = renderer(kW, kH);
  const Image image = draw(r, frame);
  ASSERT_EQ(image.pixels.size(), std::size_t(kW) * kH);

  const std::vector<bool> cpu = cpuCoverage(*camera, mesh->positions, *triangles, kW, kH);
  auto block = [&](std::uint32_t x, std::uint32_t y, bool value) {  // the 3 x 3 block around (x, y)
    for (std::uint32_t dy = y - 1; dy <= y + 1; ++dy) {
      for (std::uint32_t dx = x - 1; dx <= x + 1; ++dx) {
        if (cpu[std::size_t(dy) * kW + dx] != value) return false;
      }
    }
    return true;
  };
  std::size_t inside = 0, outside = 0;
  for (std::uint32_t y = 1; y + 1 < kH; ++y) {
    for (std::uint32_t x = 1; x + 1 < kW; ++x) {
      const std::uint8_t alpha = image.at(x, y).a;
      if (block(x, y, true)) {
        ++inside;
        EXPECT_EQ(alpha, 255) << "mesh pixel (" << x << ", " << y << ") not drawn";
      } else if (block(x, y, false)) {
        ++outside;
        EXPECT_EQ(alpha, 0) << "background pixel (" << x << ", " << y << ") drawn";
      }
    }
  }
  // The framing fills the picture: a good share of it is mesh, and there is background too.
  EXPECT_GT(inside, std::size_t(kW) * kH / 5);
  EXPECT_GT(outside, std::size_t(kW) * kH / 10);
}

TEST_F(RenderOffscreen, FlatFacesHaveTheCpuShadingColour) {
  constexpr std::uint32_t kSize = 64;
  OffscreenRenderer r = renderer(kSize, kSize);
  const Camera camera = viewSpaceCamera(1.0);
  for (const Vec3& direction : {Vec3(0, 0, 1), Vec3(-0.5, 0.6, 0.6), Vec3(0.7, -0.2, 0.5), Vec3(0.1, 0.9, 0.4)}) {
    const Vec3 n = glm::normalize(direction);
    // A square 60 wide about (0, 0, -5), normal n, covering the picture: spans u, v with u x v = n.
    const Vec3 u = glm::normalize(glm::cross(std::abs(n.y) < 0.9 ? Vec3(0, 1, 0) : Vec3(1, 0, 0), n));
    const Vec3 v = glm::cross(n, u);
    for (bool back : {false, true}) {
      // Seen from behind: the same plane with its winding and its normals reversed. The shader
      // turns the normal back towards the viewer, so the colour is the same.
      const Grid g = grid(Vec3(0, 0, -5) - 30.0 * u - 30.0 * v, 60.0 * u, 60.0 * v, 1, 1, back);
      const std::vector<SurfaceVertex> verts = vertices(g, back ? -n : n);
      FrameDraw frame;
      frame.projection = glm::mat4(camera.projection());
      frame.surfaces.push_back({verts, g.triangles, kGrey});
      const Image image = draw(r, frame);
      ASSERT_FALSE(image.empty());
      const Rgba8 expected = expectedShade(n, kGrey);
      for (std::uint32_t y : {20u, 32u, 44u}) {
        for (std::uint32_t x : {20u, 32u, 44u}) {
          EXPECT_EQ(image.at(x, y).a, 255);
          EXPECT_LE(visual::channelDistance(image.at(x, y), expected), 1)
              << "n = (" << n.x << ", " << n.y << ", " << n.z << ")" << (back ? " back face" : "") << " at " << x
              << ", " << y << ": got " << int(image.at(x, y).r) << " " << int(image.at(x, y).g) << " "
              << int(image.at(x, y).b) << ", expected " << int(expected.r) << " " << int(expected.g) << " "
              << int(expected.b);
        }
      }
    }
  }
}

TEST_F(RenderOffscreen, WithoutMultisamplingInteriorsAreUnchanged) {
  const Camera camera = viewSpaceCamera(1.0);
  const Grid g = grid(Vec3(-3, -3, -5), Vec3(6, 0, 0), Vec3(0, 6, 0), 1, 1);
  const std::vector<SurfaceVertex> verts = vertices(g, Vec3(0, 0, 1));
  FrameDraw frame;
  frame.projection = glm::mat4(camera.projection());
  frame.surfaces.push_back({verts, g.triangles, kGrey});
  OffscreenRenderer single = renderer(32, 32, 1);
  EXPECT_EQ(single.samples(), 1u);
  const Image image = draw(single, frame);
  EXPECT_LE(visual::channelDistance(image.at(16, 16), expectedShade(Vec3(0, 0, 1), kGrey)), 1);
  // Without multisampling every pixel is all or nothing.
  EXPECT_TRUE(std::all_of(image.pixels.begin(), image.pixels.end(), [](Rgba8 p) { return p.a == 0 || p.a == 255; }));
}

TEST_F(RenderOffscreen, HeatRampFollowsTheColourMapWithFallingHue) {
  constexpr std::uint32_t kW = 256, kH = 64;
  const Camera camera = viewSpaceCamera(double(kW) / kH);
  // A strip from x = -8 to 8 at z = -5 facing the camera; value = (x + 8) / 16, 0 to 1 left to right.
  const Grid g = grid(Vec3(-8, -1, -5), Vec3(16, 0, 0), Vec3(0, 2, 0), 32, 1);
  std::vector<double> values;
  for (const Vec3& p : g.positions) values.push_back((p.x + 8.0) / 16.0);
  const std::vector<SurfaceVertex> verts = vertices(g, Vec3(0, 0, 1), values);
  OffscreenRenderer r = renderer(kW, kH);
  const double left = visual::projectToPixel(camera, Vec3(-8, 0, -5), kW, kH).x;
  const double right = visual::projectToPixel(camera, Vec3(8, 0, -5), kW, kH).x;
  ASSERT_GT(left, 2.0);
  ASSERT_LT(right, kW - 2.0);

  for (float heat_max : {1.0f, 0.5f}) {
    FrameDraw frame;
    frame.projection = glm::mat4(camera.projection());
    frame.surfaces.push_back({verts, g.triangles, kGrey, true, heat_max});
    const Image image = draw(r, frame);
    ASSERT_FALSE(image.empty());
    double previous_hue = 360.0;
    double first_hue = -1.0;
    for (auto x = static_cast<std::uint32_t>(std::ceil(left)) + 1; x + 1 < right; ++x) {
      const Rgba8 pixel = image.at(x, kH / 2);
      // On a plane at one depth, screen x is affine in the value, so the CPU knows each pixel's value.
      const double value = (double(x) + 0.5 - left) / (right - left);
      const glm::vec3 heat = visual::shader::heatColour(static_cast<float>(value) / heat_max);
      const Rgba8 expected = visual::toRgba8(visual::shader::shadeColour(glm::vec3(0, 0, 1), heat));
      EXPECT_LE(visual::channelDistance(pixel, expected), 2) << "x = " << x << " value " << value;
      const double hue = visual::hueDegrees(pixel);
      if (first_hue < 0.0) first_hue = hue;
      EXPECT_LE(hue, previous_hue + 1.5) << "hue rises at x = " << x << " (heat_max " << heat_max << ")";
      previous_hue = std::min(previous_hue, hue);
    }
    EXPECT_GT(first_hue - previous_hue, 200.0) << "the ramp should run from blue to red";
    if (heat_max == 0.5f) {
      // Errors above heat_max saturate: the right quarter is one red.
      const std::uint32_t x = static_cast<std::uint32_t>(left + 0.8 * (right - left));
      EXPECT_EQ(image.at(x, kH / 2), image.at(x + 10, kH / 2));
    }
  }
}

TEST_F(RenderOffscreen, CurvesShowOnTheSurfaceAndHideBehindIt) {
  constexpr std::uint32_t kW = 200, kH = 150;
  const Camera camera = viewSpaceCamera(double(kW) / kH);
  const Grid g = grid(Vec3(-6, -5, -5), Vec3(12, 0, 0), Vec3(0, 10, 0), 4, 4);
  const std::vector<SurfaceVertex> verts = vertices(g, Vec3(0, 0, 1));
  // On the surface at y = 1; behind it at y = -1 (hidden); both colours unlit and distinct.
  const std::vector<glm::vec3> endpoints{{-2.0f, 1.0f, -5.0f}, {2.0f, 1.0f, -5.0f}, {-2.0f, -1.0f, -7.0f}, {2.0f, -1.0f, -7.0f}};
  const std::vector<glm::vec3> colours{{0.9f, 0.1f, 0.1f}, {0.1f, 0.1f, 0.9f}};
  FrameDraw frame;
  frame.projection = glm::mat4(camera.projection());
  frame.surfaces.push_back({verts, g.triangles, kGrey});
  frame.curves.push_back({endpoints, colours, 5.0f, 0.02f});
  OffscreenRenderer r = renderer(kW, kH);
  const Image image = draw(r, frame);
  ASSERT_FALSE(image.empty());
  const Rgba8 red = visual::toRgba8(colours[0]);
  const Rgba8 blue = visual::toRgba8(colours[1]);
  const Rgba8 surface = expectedShade(Vec3(0, 0, 1), kGrey);
  for (double x : {-1.5, -0.5, 0.0, 0.7, 1.6}) {
    const Vec3 on = visual::projectToPixel(camera, Vec3(x, 1.0, -5.0), kW, kH);
    EXPECT_LE(visual::channelDistance(image.at(static_cast<std::uint32_t>(on.x), static_cast<std::uint32_t>(on.y)), red), 1)
        << "x = " << x;
    const Vec3 behind = visual::projectToPixel(camera, Vec3(x, -1.0, -7.0), kW, kH);
    EXPECT_LE(visual::channelDistance(image.at(static_cast<std::uint32_t>(behind.x), static_cast<std::uint32_t>(behind.y)), surface), 1)
        << "the hidden curve shows at x = " << x;
  }
  EXPECT_EQ(std::count_if(image.pixels.begin(), image.pixels.end(),
                          [&blue](Rgba8 p) { return visual::channelDistance(p, blue) <= 1; }),
            0);
  // About five pixels wide: count the red run down the column through the line's middle.
  const Vec3 middle = visual::projectToPixel(camera, Vec3(0.0, 1.0, -5.0), kW, kH);
  int run = 0;
  for (std::uint32_t y = 0; y < kH; ++y) {
    run += visual::channelDistance(image.at(static_cast<std::uint32_t>(middle.x), y), red) <= 1 ? 1 : 0;
  }
  EXPECT_GE(run, 4);
  EXPECT_LE(run, 6);
}

TEST_F(RenderOffscreen, RejectsInconsistentDraws) {
  OffscreenRenderer r = renderer(16, 16);
  const Grid g = grid(Vec3(-1, -1, -5), Vec3(2, 0, 0), Vec3(0, 2, 0), 1, 1);
  const std::vector<SurfaceVertex> verts = vertices(g, Vec3(0, 0, 1));
  std::vector<std::uint32_t> bad = g.triangles;
  bad[4] = 4;
  FrameDraw frame;
  frame.surfaces.push_back({verts, bad, kGrey});
  Result<Image> out = r.render(frame);
  EXPECT_EQ(out.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(out.status().message().find("index 4 >= vertex count 4"), std::string::npos) << out.status().message();
  frame.surfaces = {{verts, g.triangles, kGrey, true, 0.0f}};
  EXPECT_EQ(r.render(frame).status().code(), StatusCode::kInvalidArgument);
  const std::vector<glm::vec3> endpoints(4, glm::vec3(0.0f));
  const std::vector<glm::vec3> one_colour(1, glm::vec3(1.0f));
  frame.surfaces.clear();
  frame.curves = {{endpoints, one_colour, 2.0f, 0.0f}};
  EXPECT_EQ(r.render(frame).status().code(), StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace odeskin::vk
