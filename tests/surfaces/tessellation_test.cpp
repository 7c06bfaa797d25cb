// SPDX-License-Identifier: MIT
// A network as one welded mesh: watertight (every edge where patches meet is shared by exactly two
// quads; only an open network's rim is not), no two vertices at one position, every vertex on its
// owning patch; and the editing cache re-tessellates only what an edit changes while giving
// bitwise the mesh a rebuild gives.
#include <cstdio>
#include <unordered_map>

#include <gtest/gtest.h>

#include "engine/offline/residual_fit.hpp"
#include "engine/surfaces/tessellation.hpp"
#include "engine/surfaces/tessellation_cache.hpp"
#include "surfaces/network_fixtures.hpp"

namespace odeskin {
namespace {

using testing::SweptSurface;
using testing::mixedRowShapes;
using testing::sweptLayouts;
using testing::sweptNetwork;

Network build(const SweptSurface& s) {
  Result<Network> n = Network::build(sweptNetwork(s, mixedRowShapes()));
  EXPECT_TRUE(n.ok()) << n.status().toString();
  return std::move(n).value();
}

// Pairs of distinct vertices closer than `tolerance` (spatial hash with cells of that size).
std::size_t nearDuplicates(const std::vector<Vec3>& p, double tolerance) {
  auto cell = [&](const Vec3& x) { return glm::i64vec3(glm::floor(x / tolerance)); };
  auto key = [](glm::i64vec3 c) {
    return static_cast<std::uint64_t>(c.x * 73856093) ^ static_cast<std::uint64_t>(c.y * 19349663) ^
           static_cast<std::uint64_t>(c.z * 83492791);
  };
  std::unordered_multimap<std::uint64_t, std::size_t> grid;
  for (std::size_t i = 0; i < p.size(); ++i) grid.emplace(key(cell(p[i])), i);
  std::size_t pairs = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const glm::i64vec3 c = cell(p[i]);
    for (int dx = -1; dx <= 1; ++dx) {
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dz = -1; dz <= 1; ++dz) {
          const auto [first, last] = grid.equal_range(key(c + glm::i64vec3(dx, dy, dz)));
          for (auto it = first; it != last; ++it) {
            if (it->second > i && glm::length(p[it->second] - p[i]) < tolerance) ++pairs;
          }
        }
      }
    }
  }
  return pairs;
}

TEST(Tessellation, GridSizesAndOwnership) {
  const Network tube = build(sweptLayouts()[0]);
  Result<TessellationGrid> grid = tessellationGrid(tube, {5, 7});
  ASSERT_TRUE(grid.ok());
  EXPECT_EQ(grid->gridRows(), 3u * 4u + 1u);
  EXPECT_EQ(grid->gridColumns(), 4u * 6u);  // closed in v: no extra column
  EXPECT_EQ(grid->rowOwner(4), (std::pair<std::uint32_t, std::uint32_t>{1, 0}));
  EXPECT_EQ(grid->rowOwner(12), (std::pair<std::uint32_t, std::uint32_t>{2, 4}));
  EXPECT_EQ(grid->ownedRows(2), (std::pair<std::uint32_t, std::uint32_t>{8, 13}));
  EXPECT_EQ(grid->ownedColumns(3), (std::pair<std::uint32_t, std::uint32_t>{18, 24}));
  EXPECT_EQ(tessellationGrid(tube, {1, 7}).status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(tessellationGrid(tube, {100000, 100000}).status().code(), StatusCode::kOutOfRange);
}

TEST(Tessellation, WatertightWeldedMesh) {
  for (const SweptSurface& s : sweptLayouts()) {
    const Network n = build(s);
    Result<SurfaceMesh> mesh = tessellateNetwork(n, {9, 11});
    ASSERT_TRUE(mesh.ok());
    const TessellationGrid& g = mesh->grid;
    ASSERT_EQ(mesh->positions.size(), g.vertexCount());
    // Unshared edges: exactly the rim of what is open, nothing where patches meet.
    const auto rim = unsharedEdges(mesh->faces);
    const std::size_t expected_rim = (s.closed_u ? 0 : 2 * (g.closed_v ? g.gridColumns() : g.gridColumns() - 1)) +
                                     (s.closed_v ? 0 : 2 * (g.closed_u ? g.gridRows() : g.gridRows() - 1));
    EXPECT_EQ(rim.size(), expected_rim);
    const std::uint32_t width = g.gridColumns();
    for (const auto& [a, b] : rim) {
      const bool on_u_rim = !s.closed_u && (a / width == 0 || a / width == g.gridRows() - 1) && a / width == b / width;
      const bool on_v_rim = !s.closed_v && (a % width == 0 || a % width == width - 1) && a % width == b % width;
      EXPECT_TRUE(on_u_rim || on_v_rim) << a << " " << b;
    }
    // One vertex per position, at seams too.
    const double box = longestBoxSide(mesh->positions);
    EXPECT_EQ(nearDuplicates(mesh->positions, 1e-9 * box), 0u);
    // Each vertex is its owner's S(u, v).
    double worst = 0.0;
    for (std::uint32_t gi = 0; gi < g.gridRows(); ++gi) {
      const auto [row, ui] = g.rowOwner(gi);
      for (std::uint32_t gj = 0; gj < width; ++gj) {
        const auto [column, vj] = g.columnOwner(gj);
        const Vec3 s_uv = n.evaluate(row, column, g.localU(ui), static_cast<double>(vj) / (g.v_samples - 1)).s;
        worst = std::max(worst, glm::length(mesh->positions[gi * width + gj] - s_uv));
      }
    }
    EXPECT_LE(worst, 1e-14 * box);
  }
}

TEST(Tessellation, SeamsBetweenPatchesAreWelded) {
  // Without welding, the two patches at a seam would each have a vertex there; with it the mesh has
  // exactly the grid's vertex count and every seam vertex is used by quads of both patches.
  const Network n = build(sweptLayouts()[0]);
  Result<SurfaceMesh> mesh = tessellateNetwork(n, {5, 5});
  ASSERT_TRUE(mesh.ok());
  std::vector<int> uses(mesh->positions.size(), 0);
  for (std::uint32_t index : mesh->faces.indices) ++uses[index];
  const TessellationGrid& g = mesh->grid;
  for (std::uint32_t gi = 1; gi + 1 < g.gridRows(); ++gi) {
    for (std::uint32_t gj = 0; gj < g.gridColumns(); ++gj) EXPECT_EQ(uses[gi * g.gridColumns() + gj], 4);
  }
}

TEST(Tessellation, NormalsPointAlongSuCrossSv) {
  const Network n = build(sweptLayouts()[0]);
  Result<SurfaceMesh> mesh = tessellateNetwork(n, {17, 17});
  ASSERT_TRUE(mesh.ok());
  const std::vector<Vec3> normals = vertexNormals(*mesh);
  const TessellationGrid& g = mesh->grid;
  for (std::uint32_t gi = 1; gi + 1 < g.gridRows(); gi += 7) {
    const auto [row, ui] = g.rowOwner(gi);
    for (std::uint32_t gj = 0; gj < g.gridColumns(); gj += 5) {
      const auto [column, vj] = g.columnOwner(gj);
      const PatchPoint p = n.evaluate(row, column, g.localU(ui), vj / 16.0);
      const Vec3 analytic = glm::normalize(glm::cross(p.s_u, p.s_v));
      EXPECT_GT(glm::dot(analytic, normals[gi * g.gridColumns() + gj]), 0.99);
    }
  }
}

void expectSameMesh(const SurfaceMesh& a, const SurfaceMesh& b) {
  ASSERT_EQ(a.positions.size(), b.positions.size());
  std::size_t different = 0;
  for (std::size_t i = 0; i < a.positions.size(); ++i) different += a.positions[i] != b.positions[i];
  EXPECT_EQ(different, 0u);
  EXPECT_EQ(a.faces.indices, b.faces.indices);
}

TEST(TessellationCache, EditsReevaluateOnlyTheAffectedPatches) {
  for (const SweptSurface& s : sweptLayouts()) {
    Result<NetworkTessellation> t = NetworkTessellation::create(build(s), {7, 9});
    ASSERT_TRUE(t.ok());
    const std::uint32_t columns = t->network().columns();
    EXPECT_EQ(t->update(), 0u);

    ASSERT_TRUE(t->setRowShape(1, {1, 7, 3}).ok());
    EXPECT_EQ(t->update(), columns);
    expectSameMesh(t->mesh(), *tessellateNetwork(t->network(), {7, 9}));

    // Same ratios, another rho: only that patch, and the mesh does not move.
    const SurfaceMesh before = t->mesh();
    ASSERT_TRUE(t->setPatchShape(1, 1, {2, 14, 6}).ok());
    EXPECT_EQ(t->update(), 1u);
    expectSameMesh(t->mesh(), before);
    expectSameMesh(t->mesh(), *tessellateNetwork(t->network(), {7, 9}));

    // A boundary tangent: the rows on both sides (one for an open network's first boundary).
    NetworkBoundary b = t->network().description().boundaries[0];
    ASSERT_EQ(b.source, DerivativeSource::kCoefficients);
    b.w_first = 0.6;
    ASSERT_TRUE(t->setBoundary(0, b).ok());
    EXPECT_EQ(t->update(), (s.closed_u ? 2u : 1u) * columns);
    expectSameMesh(t->mesh(), *tessellateNetwork(t->network(), {7, 9}));

    // A derivative curve measured on T (boundary 2): both rows.
    const std::uint32_t d1 = t->network().description().boundaries[2].first_curve;
    std::vector<Vec3> points = t->network().description().curve_points[d1];
    for (Vec3& p : points) p *= 1.3;
    ASSERT_TRUE(t->setCurvePoints(d1, points).ok());
    EXPECT_EQ(t->update(), 2u * columns);
    expectSameMesh(t->mesh(), *tessellateNetwork(t->network(), {7, 9}));
  }
}

TEST(TessellationCache, HundredPatchNetworkAfterOneChange) {
  // The bench's case (issue 7, point 4): 10 x 10 patches, one change, only the affected ones
  // re-evaluated, and the mesh is the one a rebuild gives.
  SweptSurface s;
  s.closed_v = false;
  s.rows = 10;
  s.columns = 10;
  s.points = 41;
  Result<Network> n = Network::build(sweptNetwork(s, {{1, 3, 1}}));
  ASSERT_TRUE(n.ok()) << n.status().toString();
  Result<NetworkTessellation> t = NetworkTessellation::create(std::move(n).value(), {17, 17});
  ASSERT_TRUE(t.ok());
  ASSERT_TRUE(t->setRowShape(4, {1, 3.5, 1}).ok());
  EXPECT_EQ(t->dirtyPatchCount(), 10u);
  EXPECT_EQ(t->update(), 10u);
  expectSameMesh(t->mesh(), *tessellateNetwork(t->network(), {17, 17}));
  NetworkBoundary b = t->network().description().boundaries[4];
  b.w_first += 0.1;
  ASSERT_TRUE(t->setBoundary(4, b).ok());
  EXPECT_EQ(t->update(), 20u);
  expectSameMesh(t->mesh(), *tessellateNetwork(t->network(), {17, 17}));
}

TEST(TessellationCache, WarnedPairingKeepsEachPatchsOwnFunctions) {
  NetworkDescription d = sweptNetwork(sweptLayouts()[0], {{1, 3, 1}});
  d.continuity = ContinuityPolicy::kWarn;
  Result<Network> n = Network::build(d);
  ASSERT_TRUE(n.ok());
  Result<NetworkTessellation> t = NetworkTessellation::create(std::move(n).value(), {6, 6});
  ASSERT_TRUE(t.ok());
  // The thesis's Fig 4.1(b) pairing, made by an edit: one patch re-evaluated.
  ASSERT_TRUE(t->setPatchShape(0, 2, {0.1, 3.0, 0.1}).ok());
  EXPECT_EQ(t->update(), 1u);
  expectSameMesh(t->mesh(), *tessellateNetwork(t->network(), {6, 6}));
}

}  // namespace
}  // namespace odeskin
