// SPDX-License-Identifier: MIT
// Where the curve rig's second pass starts (engine/rig/body_section.hpp): the body's centroid, a
// point deep inside it, and its shortest section there, on procedural tubes.
#include "engine/rig/body_section.hpp"

#include <cmath>
#include <numbers>
#include <numeric>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "rig_test_meshes.hpp"

namespace odeskin {
namespace {

using testing::TestMesh;

struct Body {
  TestMesh mesh;
  MeshTopology topology;
  std::vector<std::uint32_t> component;
  std::vector<char> in_component;
  explicit Body(TestMesh m) : mesh(std::move(m)), topology(meshTopology(mesh.positions, mesh.faces)) {
    component.resize(mesh.positions.size());
    std::iota(component.begin(), component.end(), 0u);
    in_component.assign(mesh.positions.size(), 1);
  }
};

TEST(BodySection, StraightTubeIsCutAcrossItsMiddle) {
  const Body tube(testing::closedTube(41, 16, 4.0, 0.5));
  const Vec3 centroid = bodyCentroid(tube.mesh.positions, tube.topology, tube.component, tube.in_component);
  // The volume's centroid; the triangulation (rings turned half a step in turn) is not quite
  // symmetric end to end.
  EXPECT_NEAR(centroid.x, 2.0, 1e-3);
  EXPECT_NEAR(glm::length(Vec3(0.0, centroid.y, centroid.z)), 0.0, 1e-3);
  const std::optional<GirthPlane> plane = bodySection(tube.mesh.positions, tube.topology, tube.component, tube.in_component);
  ASSERT_TRUE(plane.has_value());
  EXPECT_GT(std::abs(plane->normal.x), std::cos(std::numbers::pi / 180.0));
  EXPECT_LT(plane->girth, std::numbers::pi);
  EXPECT_GT(plane->girth, 0.98 * std::numbers::pi);
  for (const std::uint32_t v : plane->vertices) EXPECT_NEAR(tube.mesh.positions[v].x, 2.0, 0.11);
}

TEST(BodySection, CurledTubeIsCutAcrossTheTubeNotItsHole) {
  // Three quarters of a ring of radius 1.5 around the origin, tube radius 0.3: the centroid lies
  // in the hole, outside the body. The section has to go round the tube where it is thickest
  // along some line through the centroid, not round the hole.
  const double bend = 1.5;
  const double r = 0.3;
  const Body curled(testing::bentTube(61, 16, 1.5 * std::numbers::pi * bend, r, bend));
  const Vec3 centroid = bodyCentroid(curled.mesh.positions, curled.topology, curled.component, curled.in_component);
  const double from_axis = glm::length(Vec3(centroid.x, centroid.y, 0.0));
  EXPECT_LT(from_axis, bend - r) << "the centroid is in the hole";
  const std::optional<Vec3> inside =
      longestChordMiddle(curled.mesh.positions, curled.topology, curled.component, curled.in_component, centroid);
  ASSERT_TRUE(inside.has_value());
  // Inside the tube: within r of its centre circle (the caps add half a radius at the ends).
  EXPECT_LT(std::hypot(glm::length(Vec3(inside->x, inside->y, 0.0)) - bend, inside->z), r);
  const std::optional<GirthPlane> plane =
      bodySection(curled.mesh.positions, curled.topology, curled.component, curled.in_component);
  ASSERT_TRUE(plane.has_value());
  EXPECT_LT(plane->girth, 2.0 * std::numbers::pi * r * 1.02);
  EXPECT_GT(plane->girth, 2.0 * std::numbers::pi * r * 0.95);
  EXPECT_LT(std::abs(plane->normal.z), 0.05) << "the plane holds the circle's axis";
}

TEST(BodySection, SameSectionAtAnyScale) {
  // Volumes are cubes of lengths and the chords' crossings products of three: at 1e150 across they
  // overflowed, where the rest of the rig still works. Scaled by powers of two, every number
  // scales exactly, so the band must be the same vertices.
  const Body curled(testing::bentTube(61, 16, 1.5 * std::numbers::pi * 1.5, 0.3, 1.5));
  const std::optional<GirthPlane> plane =
      bodySection(curled.mesh.positions, curled.topology, curled.component, curled.in_component);
  ASSERT_TRUE(plane.has_value());
  for (const double scale : {0x1p-300, 0x1p+500}) {
    TestMesh scaled = curled.mesh;
    for (Vec3& p : scaled.positions) p *= scale;
    const Body big(std::move(scaled));
    const std::optional<GirthPlane> scaled_plane =
        bodySection(big.mesh.positions, big.topology, big.component, big.in_component);
    ASSERT_TRUE(scaled_plane.has_value()) << scale;
    EXPECT_EQ(scaled_plane->vertices, plane->vertices) << scale;
    EXPECT_EQ(scaled_plane->normal, plane->normal) << scale;
    EXPECT_EQ(scaled_plane->girth, plane->girth * scale) << scale;
  }
}

}  // namespace
}  // namespace odeskin
