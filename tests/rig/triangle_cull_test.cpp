// SPDX-License-Identifier: MIT
// The float pre-test of the centre section (engine/rig/triangle_cull.hpp): its lists must hold
// every triangle a plane or line meets, in ascending order, at any scale, and little else.
#include "engine/rig/triangle_cull.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <random>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

namespace odeskin {
namespace {

using Triangle = std::array<Vec3, 3>;

struct Soup {
  std::vector<Triangle> triangles;
  std::vector<Vec3> middles;
  std::vector<double> radii;
};

Soup soupOf(std::vector<Triangle> triangles) {
  Soup soup;
  soup.triangles = std::move(triangles);
  for (const Triangle& t : soup.triangles) {
    const Vec3 middle = (t[0] + t[1] + t[2]) / 3.0;
    double radius = 0.0;
    for (const Vec3& c : t) radius = std::max(radius, glm::length(c - middle));
    soup.middles.push_back(middle);
    soup.radii.push_back(radius);
  }
  return soup;
}

// Small triangles scattered through a ball of radius `scale` (not a multiple of 64, so the last
// block is padded), some with a corner exactly on the plane z = 0 or on the z axis.
Soup randomSoup(double scale, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<Triangle> triangles;
  for (int t = 0; t < 3001; ++t) {
    const Vec3 at(unit(rng), unit(rng), unit(rng));
    Triangle triangle;
    for (Vec3& c : triangle) c = scale * (at + 0.02 * Vec3(unit(rng), unit(rng), unit(rng)));
    if (t % 50 == 0) triangle[0].z = 0.0;
    if (t % 70 == 0) triangle[1] = Vec3(0.0, 0.0, triangle[1].z);
    triangles.push_back(triangle);
  }
  return soupOf(std::move(triangles));
}

bool planeCuts(const Triangle& t, const Vec3& normal) {
  const double a = glm::dot(normal, t[0]);
  const double b = glm::dot(normal, t[1]);
  const double c = glm::dot(normal, t[2]);
  return std::min({a, b, c}) <= 0.0 && std::max({a, b, c}) >= 0.0;
}

// The line through the origin meets the triangle: the origin lies in the triangle's shadow on the
// plane square to the line (signed areas not of both signs).
bool lineMeets(const Triangle& t, const Vec3& direction) {
  const Vec3 helper = std::abs(direction.x) < 0.6 ? Vec3(1.0, 0.0, 0.0) : Vec3(0.0, 1.0, 0.0);
  const Vec3 u = glm::normalize(glm::cross(direction, helper));
  const Vec3 w = glm::cross(direction, u);
  std::array<double, 3> x{};
  std::array<double, 3> y{};
  for (int k = 0; k < 3; ++k) {
    x[k] = glm::dot(u, t[k]);
    y[k] = glm::dot(w, t[k]);
  }
  std::array<double, 3> area{};
  for (int k = 0; k < 3; ++k) area[k] = x[(k + 1) % 3] * y[(k + 2) % 3] - y[(k + 1) % 3] * x[(k + 2) % 3];
  return !(std::min({area[0], area[1], area[2]}) < 0.0 && std::max({area[0], area[1], area[2]}) > 0.0);
}

std::vector<Vec3> directions(std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  std::vector<Vec3> out{Vec3(0.0, 0.0, 1.0)};  // through the corners put on the plane and the axis
  for (int k = 0; k < 60; ++k) out.push_back(glm::normalize(Vec3(normal(rng), normal(rng), normal(rng))));
  return out;
}

void expectHoldsEveryMet(const Soup& soup, const char* label) {
  const TriangleCull cull(soup.middles, soup.radii);
  ASSERT_EQ(cull.size(), soup.triangles.size());
  std::vector<std::uint32_t> list;
  std::size_t listed = 0;
  std::size_t met = 0;
  for (const Vec3& d : directions(7)) {
    for (const bool plane : {true, false}) {
      if (plane) {
        cull.nearPlane(d, list);
      } else {
        cull.nearLine(d, list);
      }
      ASSERT_TRUE(std::is_sorted(list.begin(), list.end())) << label;
      ASSERT_TRUE(std::adjacent_find(list.begin(), list.end()) == list.end()) << label;
      ASSERT_TRUE(list.empty() || list.back() < soup.triangles.size()) << label << ": padding listed";
      for (std::uint32_t t = 0; t < soup.triangles.size(); ++t) {
        const bool meets = plane ? planeCuts(soup.triangles[t], d) : lineMeets(soup.triangles[t], d);
        if (!meets) continue;
        ++met;
        ASSERT_TRUE(std::binary_search(list.begin(), list.end(), t))
            << label << ": triangle " << t << " is met by the " << (plane ? "plane" : "line") << " but not listed";
      }
      listed += list.size();
    }
  }
  EXPECT_GT(met, 0u) << label;
  // The balls about the triangles are a little larger than the triangles: a few more listed, but
  // far from all of them (61 planes and lines, 3001 triangles each).
  EXPECT_LT(listed, 3 * met) << label;
}

TEST(TriangleCull, ListsEveryTriangleMetInOrder) { expectHoldsEveryMet(randomSoup(1.0, 1), "unit"); }

TEST(TriangleCull, ListsEveryTriangleMetAtAnyScale) {
  expectHoldsEveryMet(randomSoup(1e-100, 2), "1e-100");
  expectHoldsEveryMet(randomSoup(1e150, 3), "1e150");
}

TEST(TriangleCull, KeepsEverythingWithoutAScale) {
  // Every triangle collapsed onto the point: no unit to measure by, so nothing may be dropped.
  const Soup soup = soupOf(std::vector<Triangle>(70, Triangle{Vec3(0.0), Vec3(0.0), Vec3(0.0)}));
  const TriangleCull cull(soup.middles, soup.radii);
  std::vector<std::uint32_t> list;
  cull.nearPlane(Vec3(0.0, 0.0, 1.0), list);
  EXPECT_EQ(list.size(), 70u);
  cull.nearLine(Vec3(1.0, 0.0, 0.0), list);
  EXPECT_EQ(list.size(), 70u);
}

TEST(TriangleCull, EmptyListsNothing) {
  const TriangleCull cull({}, {});
  std::vector<std::uint32_t> list{5};
  cull.nearPlane(Vec3(0.0, 0.0, 1.0), list);
  EXPECT_TRUE(list.empty());
}

}  // namespace
}  // namespace odeskin
