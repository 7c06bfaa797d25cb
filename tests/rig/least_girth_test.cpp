// SPDX-License-Identifier: MIT
// The shortest section of a body through a point (engine/rig/least_girth.hpp), on procedural
// tubes: where the curve rig's second pass starts.
#include "engine/rig/least_girth.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <random>
#include <utility>

#include <gtest/gtest.h>

#include "engine/rig/mesh_topology.hpp"
#include "rig_test_meshes.hpp"

namespace odeskin {
namespace {

using testing::closedTube;
using testing::TestMesh;

// Oblique starts, so that the pattern search has to find the axis itself.
const std::vector<Vec3> kObliqueStarts{Vec3(1.0, 1.0, 0.0), Vec3(0.0, 1.0, 1.0)};

TEST(LeastGirth, TubeIsCutSquareAcrossItsAxis) {
  // Radius 0.5, rings 0.1 apart; the centre between two rings. The section across the axis is a
  // polygon inscribed in the circle of length pi; any slanted one is an ellipse, longer.
  const TestMesh tube = closedTube(41, 16, 4.0, 0.5);
  const MeshTopology mesh = meshTopology(tube.positions, tube.faces);
  const Vec3 centre(2.05, 0.0, 0.0);
  const std::optional<GirthPlane> plane = leastGirthPlane(tube.positions, mesh, centre, 1.5, kObliqueStarts);
  ASSERT_TRUE(plane.has_value());
  EXPECT_GT(std::abs(plane->normal.x), std::cos(std::numbers::pi / 180.0)) << "within a degree of the axis";
  EXPECT_LT(plane->girth, std::numbers::pi);
  EXPECT_GT(plane->girth, 0.98 * std::numbers::pi);
  // The band: both rings either side of the plane, each vertex with its distance to the plane.
  ASSERT_EQ(plane->vertices.size(), 32u);
  ASSERT_EQ(plane->distances.size(), 32u);
  EXPECT_TRUE(std::is_sorted(plane->vertices.begin(), plane->vertices.end()));
  for (std::size_t k = 0; k < plane->vertices.size(); ++k) {
    const Vec3& p = tube.positions[plane->vertices[k]];
    EXPECT_TRUE(std::abs(p.x - 2.0) < 1e-12 || std::abs(p.x - 2.1) < 1e-12) << p.x;
    EXPECT_NEAR(plane->distances[k], std::abs(glm::dot(plane->normal, p - centre)), 1e-15);
    EXPECT_LT(plane->distances[k], 0.06);
  }
}

TEST(LeastGirth, NoSectionAroundAPointOutsideTheBody) {
  const TestMesh tube = closedTube(41, 16, 4.0, 0.5);
  const MeshTopology mesh = meshTopology(tube.positions, tube.faces);
  EXPECT_FALSE(leastGirthPlane(tube.positions, mesh, Vec3(2.05, 1.0, 0.0), 1.5, kObliqueStarts).has_value());
  // Nothing within reach at all.
  EXPECT_FALSE(leastGirthPlane(tube.positions, mesh, Vec3(2.05, 0.0, 0.0), 0.1, kObliqueStarts).has_value());
}

TEST(LeastGirth, NoSectionAroundAPointInAHollowCore) {
  // A pipe: an outer tube, and an inner one facing inward (its triangles reversed). A point on the
  // axis is in the hollow, outside the material: every plane through it meets two loops around it
  // (the pipe's outer and inner walls), an even count.
  TestMesh pipe = closedTube(41, 16, 4.0, 1.0);
  const TestMesh core = closedTube(41, 16, 4.0, 0.5);
  const auto offset = static_cast<std::uint32_t>(pipe.positions.size());
  pipe.positions.insert(pipe.positions.end(), core.positions.begin(), core.positions.end());
  for (std::size_t f = 0; f + 1 < core.faces.face_offsets.size(); ++f) {
    const std::uint32_t* c = &core.faces.indices[core.faces.face_offsets[f]];
    pipe.triangle(offset + c[0], offset + c[2], offset + c[1]);
  }
  const MeshTopology mesh = meshTopology(pipe.positions, pipe.faces);
  EXPECT_FALSE(leastGirthPlane(pipe.positions, mesh, Vec3(2.05, 0.0, 0.0), 3.0, kObliqueStarts).has_value());
}

TEST(LeastGirth, FinsOnTheSurfaceLeaveTheLoopClosed) {
  // A fin (a third triangle) on every axial edge of the rings either side of the section: the
  // plane crosses each fin, whose piece dangles from the loop, and the loop still counts.
  TestMesh tube = closedTube(41, 16, 4.0, 0.5);
  for (std::uint32_t k = 0; k < 16; ++k) {
    const std::uint32_t a = 20 * 16 + k;
    const auto fin = static_cast<std::uint32_t>(tube.positions.size());
    tube.positions.push_back(tube.positions[a] + Vec3(0.05, 0.0, 0.6));
    tube.triangle(a, a + 16, fin);
  }
  const MeshTopology mesh = meshTopology(tube.positions, tube.faces);
  const std::optional<GirthPlane> plane =
      leastGirthPlane(tube.positions, mesh, Vec3(2.05, 0.0, 0.0), 1.5, std::vector<Vec3>{Vec3(1.0, 0.0, 0.0)});
  ASSERT_TRUE(plane.has_value());
  EXPECT_LT(plane->girth, std::numbers::pi);
  EXPECT_GT(plane->girth, 0.98 * std::numbers::pi);
}

TEST(LeastGirth, TrianglesFacingEitherWayGiveTheSameSection) {
  // Every other triangle turned over: a loop's pieces then run either way round, and whether the
  // loop goes round the centre is told by the parity of a ray's crossings, not by a winding number.
  const TestMesh tube = closedTube(41, 16, 4.0, 0.5);
  TestMesh mixed = tube;
  for (std::size_t f = 0; f + 1 < mixed.faces.face_offsets.size(); f += 2) {
    std::swap(mixed.faces.indices[mixed.faces.face_offsets[f] + 1], mixed.faces.indices[mixed.faces.face_offsets[f] + 2]);
  }
  const Vec3 centre(2.05, 0.0, 0.0);
  const std::optional<GirthPlane> a =
      leastGirthPlane(tube.positions, meshTopology(tube.positions, tube.faces), centre, 1.5, kObliqueStarts);
  const std::optional<GirthPlane> b =
      leastGirthPlane(mixed.positions, meshTopology(mixed.positions, mixed.faces), centre, 1.5, kObliqueStarts);
  ASSERT_TRUE(a.has_value());
  ASSERT_TRUE(b.has_value());
  EXPECT_EQ(a->girth, b->girth);
  EXPECT_EQ(a->vertices, b->vertices);
}

TEST(LeastGirth, SameSectionWhateverTheVertexOrder) {
  const TestMesh tube = closedTube(41, 16, 4.0, 0.5);
  std::vector<std::uint32_t> order(tube.positions.size());  // order[i]: the new index of vertex i
  std::iota(order.begin(), order.end(), 0u);
  std::shuffle(order.begin(), order.end(), std::mt19937(7));
  TestMesh renumbered;
  renumbered.positions.resize(tube.positions.size());
  for (std::size_t i = 0; i < order.size(); ++i) renumbered.positions[order[i]] = tube.positions[i];
  renumbered.faces = tube.faces;
  for (std::uint32_t& v : renumbered.faces.indices) v = order[v];

  const Vec3 centre(1.37, 0.05, -0.02);
  const MeshTopology mesh = meshTopology(tube.positions, tube.faces);
  const MeshTopology renumbered_mesh = meshTopology(renumbered.positions, renumbered.faces);
  const std::optional<GirthPlane> a = leastGirthPlane(tube.positions, mesh, centre, 1.5, kObliqueStarts);
  const std::optional<GirthPlane> b = leastGirthPlane(renumbered.positions, renumbered_mesh, centre, 1.5, kObliqueStarts);
  ASSERT_TRUE(a.has_value());
  ASSERT_TRUE(b.has_value());
  EXPECT_EQ(a->normal, b->normal);
  EXPECT_EQ(a->girth, b->girth);
  std::vector<std::uint32_t> mapped;
  for (const std::uint32_t v : a->vertices) mapped.push_back(order[v]);
  std::sort(mapped.begin(), mapped.end());
  EXPECT_EQ(mapped, b->vertices);
}

}  // namespace
}  // namespace odeskin
