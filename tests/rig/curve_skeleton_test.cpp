// SPDX-License-Identifier: MIT
#include "engine/rig/curve_skeleton.hpp"

#include <cmath>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "engine/core/disjoint_sets.hpp"
#include "engine/io/obj_reader.hpp"
#include "engine/rig/curve_skeleton_levels.hpp"
#include "engine/rig/curve_skeleton_parts.hpp"
#include "engine/rig/curve_skeleton_tree.hpp"
#include "engine/rig/mesh_topology.hpp"
#include "engine/rig/surface_distance.hpp"
#include "engine/data_mesh.hpp"  // tests/engine
#include "rig_test_meshes.hpp"

namespace odeskin {
namespace {

using testing::closedTube;
using testing::dataMesh;
using testing::flatGrid;

std::size_t countKind(const CurveSkeleton& s, SkeletonNodeKind kind) {
  std::size_t n = 0;
  for (const SkeletonNodeKind k : s.kinds) n += k == kind ? 1 : 0;
  return n;
}

TEST(CurveSkeleton, RejectsBadInput) {
  const testing::TestMesh tube = closedTube(20, 12, 4.0, 0.5);
  EXPECT_EQ(buildCurveSkeleton({}, tube.faces).status().code(), StatusCode::kInvalidArgument);
  std::vector<Vec3> bad = tube.positions;
  bad[3].y = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(buildCurveSkeleton(bad, tube.faces).status().code(), StatusCode::kInvalidArgument);
  FaceList out_of_range = tube.faces;
  out_of_range.indices[5] = static_cast<std::uint32_t>(tube.positions.size());
  const Status s = buildCurveSkeleton(tube.positions, out_of_range).status();
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(s.message().find("face 1"), std::string::npos) << s.message();
  CurveSkeletonOptions options;
  options.level_spacing = -1.0;
  EXPECT_EQ(buildCurveSkeleton(tube.positions, tube.faces, options).status().code(), StatusCode::kInvalidArgument);
  options = {};
  options.prune_fraction = 1.5;
  EXPECT_EQ(buildCurveSkeleton(tube.positions, tube.faces, options).status().code(), StatusCode::kInvalidArgument);
  // Finite, but so large that squared lengths overflow (this crashed in the level tree before the check).
  std::vector<Vec3> huge = tube.positions;
  for (Vec3& p : huge) p *= 1e200;
  const Status too_large = buildCurveSkeleton(huge, tube.faces).status();
  EXPECT_EQ(too_large.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(too_large.message().find("too large"), std::string::npos) << too_large.message();
  for (Vec3& p : huge) p *= 1e-200 * 1e150;  // squares still finite: rigged as the tube
  EXPECT_TRUE(buildCurveSkeleton(huge, tube.faces).ok());
}

TEST(CurveSkeleton, TopologyOfACube) {
  // 8 corners, 6 quads: 12 triangles, 18 edges, each between two triangles.
  const std::vector<Vec3> corners{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0),
                                  Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(1, 1, 1), Vec3(0, 1, 1)};
  FaceList quads;
  quads.indices = {0, 3, 2, 1, 4, 5, 6, 7, 0, 1, 5, 4, 1, 2, 6, 5, 2, 3, 7, 6, 3, 0, 4, 7};
  quads.face_offsets = {0, 4, 8, 12, 16, 20, 24};
  const MeshTopology mesh = meshTopology(corners, quads);
  EXPECT_EQ(mesh.triangles.size(), 12u);
  ASSERT_EQ(mesh.edges.size(), 18u);
  // Edges in order of (smaller end, larger end), each with its triangles in index order: the
  // numbering every later table, and the order of the level graphs' regions and rings, rests on.
  for (std::size_t e = 0; e + 1 < mesh.edges.size(); ++e) EXPECT_LT(mesh.edges[e], mesh.edges[e + 1]) << e;
  for (const auto& t : mesh.edge_triangles) {
    EXPECT_GE(t[1], 0);
    EXPECT_LT(t[0], t[1]);
  }
  for (const char b : mesh.boundary_vertex) EXPECT_EQ(b, 0);
  EXPECT_EQ(mesh.vertex_offsets.back(), 36u);
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const auto& e = mesh.edges[mesh.triangle_edges[t][static_cast<std::size_t>(k)]];
      const std::uint32_t a = mesh.triangles[t][static_cast<std::size_t>(k)];
      const std::uint32_t b = mesh.triangles[t][static_cast<std::size_t>((k + 1) % 3)];
      EXPECT_EQ(e[0], std::min(a, b));
      EXPECT_EQ(e[1], std::max(a, b));
    }
  }
}

TEST(CurveSkeleton, FlattenedSetsPointAtTheirSmallestMember) {
  // The level graph reads parent[] directly after flatten(): it must be find() for every member,
  // and that root the smallest member, whatever order the unions came in.
  DisjointSets sets(40);
  const std::uint32_t pairs[][2] = {{39, 7}, {7, 21}, {21, 30}, {5, 38}, {38, 30}, {12, 13}, {13, 2}, {33, 34}, {34, 35}};
  for (const auto& p : pairs) sets.unite(p[0], p[1]);
  DisjointSets reference = sets;
  sets.flatten();
  for (std::uint32_t x = 0; x < 40; ++x) EXPECT_EQ(sets.parent[x], reference.find(x)) << x;
  for (const std::uint32_t x : {39u, 7u, 21u, 30u, 38u}) EXPECT_EQ(sets.parent[x], 5u);
  EXPECT_EQ(sets.parent[13], 2u);
  EXPECT_EQ(sets.parent[35], 33u);
  EXPECT_EQ(sets.parent[17], 17u);
}

TEST(CurveSkeleton, FastMarchingBeatsEdgePathsOnAGrid) {
  // Distance from the left column of a grid is exactly x; edge paths get it right too, but from a
  // corner the diagonal front is where edge paths overshoot (sqrt 2 vs 2 along the other diagonal).
  const testing::TestMesh grid = flatGrid(20);
  const MeshTopology mesh = meshTopology(grid.positions, grid.faces);
  std::vector<std::uint32_t> column;
  for (std::uint32_t j = 0; j <= 20; ++j) column.push_back(j * 21);
  const std::vector<double> d = surfaceDistance(mesh, grid.positions, column);
  for (std::size_t v = 0; v < d.size(); ++v) EXPECT_NEAR(d[v], grid.positions[v].x, 1e-12);
  const std::uint32_t corner[1] = {0};
  const std::vector<double> fmm = surfaceDistance(mesh, grid.positions, corner);
  const std::vector<double> edges = edgeDistance(mesh, corner);
  double fmm_error = 0.0, edge_error = 0.0;
  for (std::size_t v = 0; v < d.size(); ++v) {
    const double exact = glm::length(grid.positions[v]);
    EXPECT_GE(fmm[v], exact - 1e-9);
    fmm_error = std::max(fmm_error, fmm[v] - exact);
    edge_error = std::max(edge_error, edges[v] - exact);
  }
  EXPECT_LT(fmm_error, 0.5 * edge_error);
  const std::vector<std::int32_t> hops = edgeHops(mesh, 0);
  EXPECT_EQ(hops[20], 20);      // along the bottom row
  EXPECT_EQ(hops[440], 20);     // the far corner, along the diagonals
}

TEST(CurveSkeleton, HopSweepCountsOneComponentAndStopsAtCountedVertices) {
  // Two 4 x 4 grids side by side, not connected: 25 vertices each.
  testing::TestMesh two = flatGrid(4);
  const testing::TestMesh second = flatGrid(4);
  const auto offset = static_cast<std::uint32_t>(two.positions.size());
  for (const Vec3& p : second.positions) two.positions.push_back(p + Vec3(10.0, 0.0, 0.0));
  for (std::size_t f = 0; f < second.faces.faceCount(); ++f) {
    const std::uint32_t* c = &second.faces.indices[second.faces.face_offsets[f]];
    two.triangle(c[0] + offset, c[1] + offset, c[2] + offset);
  }
  const MeshTopology mesh = meshTopology(two.positions, two.faces);
  std::vector<std::int32_t> hops(two.positions.size(), -1);
  std::vector<std::uint32_t> queue(two.positions.size() + 1);
  const std::size_t first = sweepEdgeHops(mesh, 0, hops, queue);
  ASSERT_EQ(first, 25u);
  for (std::size_t k = 1; k < first; ++k) EXPECT_LE(hops[queue[k - 1]], hops[queue[k]]) << k;
  // The grid's diagonals run (+1, +1): (i, j) is max(i, j) hops from the corner (0, 0).
  EXPECT_EQ(hops[queue[first - 1]], 4);
  EXPECT_EQ(hops[24], 4);
  for (std::uint32_t v = offset; v < two.positions.size(); ++v) EXPECT_EQ(hops[v], -1) << v;
  // The second grid from its centre; the first keeps its counts.
  const std::size_t centre = sweepEdgeHops(mesh, offset + 12, hops, queue);
  ASSERT_EQ(centre, 25u);
  EXPECT_EQ(queue[0], offset + 12);
  EXPECT_EQ(hops[offset + 12], 0);
  EXPECT_EQ(hops[offset], 2);      // (0, 0): two diagonals back
  EXPECT_EQ(hops[offset + 4], 4);  // (4, 0): no diagonal runs (+1, -1)
  EXPECT_EQ(hops[24], 4);
}

// A contour whose points are numbered 0..n-1 with point i on edge (i, i + 1) at t = 0.5.
LevelContour contourOf(std::size_t n, std::vector<std::array<std::uint32_t, 2>> segments, bool closed) {
  LevelContour c;
  for (std::uint32_t i = 0; i < n; ++i) c.points.push_back({i, i + 1, 0.5});
  c.segments = std::move(segments);
  c.closed = closed;
  return c;
}

std::vector<std::uint32_t> walk(const LevelContour& contour) {
  std::vector<std::uint32_t> order;
  for (const CurvePoint& p : orderedContour(contour, 3).points) order.push_back(p.a);
  return order;
}

TEST(CurveSkeleton, OrderedContourWalksARingFromPointZeroTowardsItsFirstSegment) {
  // The ring 0-2-4-1-3-0, its segments in no order; point 0's first segment is (3, 0).
  const LevelContour ring = contourOf(5, {{1, 4}, {3, 0}, {2, 4}, {0, 2}, {1, 3}}, true);
  EXPECT_EQ(walk(ring), (std::vector<std::uint32_t>{0, 3, 1, 4, 2}));
  const IsoCurve curve = orderedContour(ring, 3);
  EXPECT_TRUE(curve.closed);
  EXPECT_EQ(curve.part, 3u);
  // Two points joined by two segments (a level through a fin of two triangles) stay two points.
  EXPECT_EQ(walk(contourOf(2, {{0, 1}, {1, 0}}, true)), (std::vector<std::uint32_t>{0, 1}));
}

TEST(CurveSkeleton, OrderedContourWalksAnArcFromItsFirstEnd) {
  // The arc 3-0-4-2-1: its ends are 1 and 3, and the walk starts at the lower-numbered one.
  const LevelContour arc = contourOf(5, {{4, 2}, {0, 3}, {1, 2}, {0, 4}}, false);
  EXPECT_EQ(walk(arc), (std::vector<std::uint32_t>{1, 2, 4, 0, 3}));
  EXPECT_FALSE(orderedContour(arc, 0).closed);
  EXPECT_EQ(walk(contourOf(2, {{1, 0}}, false)), (std::vector<std::uint32_t>{0, 1}));
}

TEST(CurveSkeleton, OrderedContourThroughANonManifoldEdgeKeepsFirstAndLastNeighbours) {
  // Point 1 ends three segments (a level through an edge of three triangles): it keeps its first
  // neighbour (0) and its last (3); the walk starts at the end 3 and stops where it meets a point
  // already taken.
  EXPECT_EQ(walk(contourOf(4, {{0, 1}, {1, 2}, {2, 0}, {1, 3}}, false)), (std::vector<std::uint32_t>{3, 1, 0, 2}));
}

TEST(CurveSkeleton, NonManifoldFinsGiveATubesSkeleton) {
  // Fins hung on 30 of a tube's axial edges (three triangles on each): the levels cross them, and
  // their rings have points on three segments.
  testing::TestMesh tube = closedTube(41, 16, 4.0, 0.5);
  for (std::uint32_t i = 5; i < 35; ++i) {
    const std::uint32_t a = i * 16;  // ring i's first vertex; ring i + 1's is a + 16
    const auto fin = static_cast<std::uint32_t>(tube.positions.size());
    tube.positions.push_back(tube.positions[a] + Vec3(0.05, 0.0, 0.6));
    tube.triangle(a, a + 16, fin);
  }
  Result<CurveSkeletonResult> r = buildCurveSkeleton(tube.positions, tube.faces);
  ASSERT_TRUE(r.ok()) << r.status().message();
  EXPECT_EQ(countKind(r->skeleton, SkeletonNodeKind::kTip), 2u);
  EXPECT_EQ(countKind(r->skeleton, SkeletonNodeKind::kJunction), 0u);
  ASSERT_FALSE(r->curves.empty());
  for (const IsoCurve& curve : r->curves) {
    ASSERT_FALSE(curve.points.empty());
    for (const CurvePoint& p : curve.points) {
      EXPECT_LT(p.a, tube.positions.size());
      EXPECT_LT(p.b, tube.positions.size());
    }
  }
}

TEST(CurveSkeleton, CurveNodeIsTheLengthWeightedCentroid) {
  // A closed square of side 1 with an extra point halfway along its first side: the anchors weigh
  // half of each segment at either end, so the node is the square's centre, not the points' mean.
  const std::vector<Vec3> rest{Vec3(0, 0, 0), Vec3(0.5, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)};
  std::vector<CurvePoint> points;
  for (std::uint32_t i = 0; i < 5; ++i) points.push_back({i, i, 0.0});
  CurveSkeleton s;
  addCurveNode(s, SkeletonNodeKind::kCurve, -1, 2, 0.25, points, true, rest);
  ASSERT_EQ(s.nodeCount(), 1u);
  EXPECT_NEAR(glm::length(s.positions[0] - Vec3(0.5, 0.5, 0.0)), 0.0, 1e-15);
  EXPECT_EQ(s.parts[0], 2u);
  EXPECT_EQ(s.radii[0], 0.25);
  ASSERT_EQ(s.anchor_offsets, (std::vector<std::uint32_t>{0, 5}));
  const double expected[5] = {0.75, 0.5, 0.75, 1.0, 1.0};
  for (std::size_t i = 0; i < 5; ++i) EXPECT_DOUBLE_EQ(s.anchors[i].weight, expected[i]) << i;
  // Open, the last side is left out; a curve of no length weighs its points equally.
  addCurveNode(s, SkeletonNodeKind::kCurve, 0, 2, 0.0, points, false, rest);
  EXPECT_DOUBLE_EQ(s.anchors[5].weight, 0.25);
  EXPECT_DOUBLE_EQ(s.anchors[9].weight, 0.5);
  const std::vector<Vec3> collapsed(5, Vec3(2.0, 0.0, 0.0));
  addCurveNode(s, SkeletonNodeKind::kCurve, 1, 2, 0.0, points, true, collapsed);
  EXPECT_EQ(s.positions[2], Vec3(2.0, 0.0, 0.0));
  for (std::size_t i = 10; i < 15; ++i) EXPECT_EQ(s.anchors[i].weight, 1.0);
  EXPECT_EQ(s.anchor_offsets.back(), 15u);
  // A single point is its own node at weight 1, closed or open.
  for (const bool closed : {true, false}) {
    addCurveNode(s, SkeletonNodeKind::kCurve, 2, 2, 0.0, std::span(points).subspan(3, 1), closed, rest);
    EXPECT_EQ(s.positions.back(), rest[3]);
    EXPECT_EQ(s.anchors.back().weight, 1.0);
  }
  EXPECT_EQ(s.anchor_offsets.back(), 17u);
  // The skeleton's positions on the rest mesh reproduce the nodes from the anchors.
  const std::vector<Vec3> again = curveSkeletonPositions(s, rest);
  for (std::size_t n = 0; n < 2; ++n) EXPECT_NEAR(glm::length(again[n] - s.positions[n]), 0.0, 1e-15) << n;
}

TEST(CurveSkeleton, RingsOfATubeAreClosedAndJoinTheirRegions) {
  const testing::TestMesh tube = closedTube(41, 16, 4.0, 0.5);
  const MeshTopology mesh = meshTopology(tube.positions, tube.faces);
  const std::uint32_t start[1] = {static_cast<std::uint32_t>(tube.positions.size() - 2)};  // the x = -0.25 cap
  const std::vector<double> f = surfaceDistance(mesh, tube.positions, start);
  const LevelGraph graph = levelGraph(tube.positions, mesh, f, 0.3);
  ASSERT_GT(graph.contours.size(), 10u);
  for (const LevelContour& c : graph.contours) {
    EXPECT_TRUE(c.closed);
    EXPECT_EQ(graph.regions[c.lower].slab + 1, graph.regions[c.upper].slab);
    // A ring across the tube: centred on the axis, of the tube's radius (away from the caps).
    if (c.centroid.x > 0.5 && c.centroid.x < 3.5) {
      EXPECT_NEAR(c.centroid.y, 0.0, 0.02);
      EXPECT_NEAR(c.centroid.z, 0.0, 0.02);
      EXPECT_NEAR(c.radius, 0.5, 0.03);
    }
  }
  // A tube's graph is a chain: every region but the two ends has two contours.
  std::size_t ends = 0;
  for (const LevelRegion& r : graph.regions) {
    EXPECT_LE(r.contours.size(), 2u);
    ends += r.contours.size() == 1 ? 1 : 0;
  }
  EXPECT_EQ(ends, 2u);
}

TEST(CurveSkeleton, RingRadiusIsTheMeanOfTheKeptRings) {
  const testing::TestMesh tube = closedTube(41, 16, 4.0, 0.5);
  const MeshTopology mesh = meshTopology(tube.positions, tube.faces);
  const std::uint32_t start[1] = {static_cast<std::uint32_t>(tube.positions.size() - 2)};
  const std::vector<double> f = surfaceDistance(mesh, tube.positions, start);
  const LevelGraph graph = levelGraph(tube.positions, mesh, f, 0.3);
  const LevelTree tree = levelTree(graph, graph.vertex_region[start[0]], PruneRule{});
  for (std::uint32_t r = 0; r < graph.regions.size(); ++r) {
    double sum = 0.0;
    double n = 0.0;
    for (const std::uint32_t c : graph.regions[r].contours) {
      sum += graph.contours[c].radius;
      n += 1.0;
    }
    ASSERT_GT(n, 0.0) << r;  // a chain: every contour is kept
    EXPECT_DOUBLE_EQ(tree.ringRadius(graph, r, -1.0), sum / n) << r;
  }
  // Levels further apart than the tube is long: one region, no ring, the fallback.
  const LevelGraph whole = levelGraph(tube.positions, mesh, f, 100.0);
  ASSERT_EQ(whole.regions.size(), 1u);
  const LevelTree single = levelTree(whole, 0, PruneRule{});
  EXPECT_EQ(single.ringRadius(whole, 0, 0.25), 0.25);
}

TEST(CurveSkeleton, TubeSkeletonRunsAlongItsAxis) {
  const testing::TestMesh tube = closedTube(41, 16, 4.0, 0.5);
  for (const CurveSource source : {CurveSource::kLevels, CurveSource::kPlaneCuts}) {
    CurveSkeletonOptions options;
    options.source = source;
    Result<CurveSkeletonResult> r = buildCurveSkeleton(tube.positions, tube.faces, options);
    ASSERT_TRUE(r.ok()) << r.status().message();
    const CurveSkeleton& s = r->skeleton;
    EXPECT_EQ(countKind(s, SkeletonNodeKind::kJunction), 0u);
    EXPECT_EQ(countKind(s, SkeletonNodeKind::kTip), 2u);
    ASSERT_GE(s.nodeCount(), 10u);  // the plane cuts place 7 rings on this tube, the levels 61
    double lo = 1e9, hi = -1e9;
    for (std::size_t n = 0; n < s.nodeCount(); ++n) {
      EXPECT_LT(std::hypot(s.positions[n].y, s.positions[n].z), 0.05) << "node " << n;
      EXPECT_LT(s.parents[n], static_cast<std::int32_t>(n));
      lo = std::min(lo, s.positions[n].x);
      hi = std::max(hi, s.positions[n].x);
    }
    EXPECT_EQ(s.parents[0], -1);
    EXPECT_LT(lo, 0.2);  // the tips reach into the caps
    EXPECT_GT(hi, 3.8);
    EXPECT_FALSE(r->curves.empty());
    EXPECT_EQ(r->vertex_parts.size(), tube.positions.size());
  }
}

TEST(CurveSkeleton, NodesFollowAnyPoseOfTheMesh) {
  const ObjMesh cat = dataMesh("cat-poses/cat-00.obj");
  Result<CurveSkeletonResult> r = buildCurveSkeleton(cat.positions, cat.faces);
  ASSERT_TRUE(r.ok()) << r.status().message();
  const CurveSkeleton& s = r->skeleton;
  const std::vector<Vec3> same = curveSkeletonPositions(s, cat.positions);
  std::vector<Vec3> moved = cat.positions;
  for (Vec3& p : moved) p += Vec3(1.0, -2.0, 3.0);
  const std::vector<Vec3> shifted = curveSkeletonPositions(s, moved);
  for (std::size_t n = 0; n < s.nodeCount(); ++n) {
    EXPECT_NEAR(glm::length(same[n] - s.positions[n]), 0.0, 1e-12);
    EXPECT_NEAR(glm::length(shifted[n] - s.positions[n] - Vec3(1.0, -2.0, 3.0)), 0.0, 1e-12);
  }
}

TEST(CurveSkeleton, CatHasFourLegsATailAndAHead) {
  const ObjMesh cat = dataMesh("cat-poses/cat-00.obj");
  Result<CurveSkeletonResult> r = buildCurveSkeleton(cat.positions, cat.faces);
  ASSERT_TRUE(r.ok()) << r.status().message();
  // Six free ends: four paws, the tail and the head (ears and toes are pruned as bumps or join
  // the head's end).
  std::size_t ends = 0;
  std::vector<int> degree(r->skeleton.nodeCount(), 0);
  for (std::size_t n = 1; n < r->skeleton.nodeCount(); ++n) {
    ++degree[n];
    ++degree[static_cast<std::size_t>(r->skeleton.parents[n])];
  }
  for (const int d : degree) ends += d == 1 ? 1 : 0;
  EXPECT_GE(ends, 6u);
  EXPECT_LE(ends, 8u);
  EXPECT_GE(countKind(r->skeleton, SkeletonNodeKind::kJunction), 1u);
  EXPECT_EQ(r->unreached_vertices, 0u);
}

TEST(CurveSkeleton, OpenEndsEndAtTheRimCentre) {
  // The cylinder of the data is open at x = +-2: its tips are the rims' centres.
  const ObjMesh cylinder = dataMesh("cylinder/cylinder.obj");
  Result<CurveSkeletonResult> r = buildCurveSkeleton(cylinder.positions, cylinder.faces);
  ASSERT_TRUE(r.ok()) << r.status().message();
  std::vector<double> tips;
  for (std::size_t n = 0; n < r->skeleton.nodeCount(); ++n) {
    if (r->skeleton.kinds[n] != SkeletonNodeKind::kTip) continue;
    tips.push_back(r->skeleton.positions[n].x);
    EXPECT_LT(std::hypot(r->skeleton.positions[n].y, r->skeleton.positions[n].z), 1e-6);  // the file has 7 digits
  }
  ASSERT_EQ(tips.size(), 2u);
  EXPECT_NEAR(std::abs(tips[0]), 2.0, 1e-6);
  EXPECT_NEAR(std::abs(tips[1]), 2.0, 1e-6);
}

}  // namespace
}  // namespace odeskin
