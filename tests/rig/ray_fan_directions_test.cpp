// SPDX-License-Identifier: MIT
// The ray-and-fan test (thesis 5.3) on quad meshes with a known parameterisation, and the curve rig
// that reads its skeleton off their edge loops.
#include "engine/curves/ray_fan_directions.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <string>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "engine/io/obj_io.hpp"
#include "engine/io/obj_reader.hpp"
#include "engine/rig/curve_rig.hpp"
#include "engine/visual/camera.hpp"
#include "quad_test_meshes.hpp"

namespace odeskin {
namespace {

using testing::QuadTestMesh;

PolyMesh polyMesh(const QuadTestMesh& m) {
  Result<PolyMesh> mesh = buildPolyMesh(m.positions, m.faces, "test mesh");
  if (!mesh.ok()) throw std::runtime_error(mesh.status().toString());
  return std::move(mesh).value();
}

struct Accuracy {
  std::size_t right = 0;
  std::size_t known = 0;
  double fraction() const { return known > 0 ? static_cast<double>(right) / static_cast<double>(known) : 0.0; }
};

// Against the sweep's rings: an edge within one ring is circumferential, one between rings at the
// same position round them axial (edges at the poles have neither and are not counted).
Accuracy ringAccuracy(const QuadTestMesh& m, const PolyMesh& mesh, const RayFanDirections& d) {
  Accuracy a;
  for (auto e : mesh.edges()) {
    const auto u = static_cast<std::size_t>(e.v0().idx());  // the ends of halfedge 0
    const auto v = static_cast<std::size_t>(e.v1().idx());
    if (m.ring[u] < 0 || m.ring[v] < 0) continue;
    const EdgeDirection truth = m.ring[u] == m.ring[v] ? EdgeDirection::kCircumferential : EdgeDirection::kAxial;
    ++a.known;
    a.right += d.edges[static_cast<std::size_t>(e.idx())] == truth ? 1 : 0;
  }
  return a;
}

// Against a per-vertex true axis (both ends must have the same one): the edge's side of 45 degrees.
Accuracy axisAccuracy(const QuadTestMesh& m, const PolyMesh& mesh, const RayFanDirections& d) {
  Accuracy a;
  for (auto e : mesh.edges()) {
    const auto u = static_cast<std::size_t>(e.v0().idx());  // the ends of halfedge 0
    const auto v = static_cast<std::size_t>(e.v1().idx());
    if (!(glm::length(m.axis[u]) > 0.0) || m.axis[u] != m.axis[v]) continue;
    const Vec3 edge = glm::normalize(m.positions[v] - m.positions[u]);
    const EdgeDirection truth =
        std::abs(glm::dot(edge, m.axis[u])) > std::sqrt(0.5) ? EdgeDirection::kAxial : EdgeDirection::kCircumferential;
    ++a.known;
    a.right += d.edges[static_cast<std::size_t>(e.idx())] == truth ? 1 : 0;
  }
  return a;
}

// The meshes `odeskin rig` is run on in docs/rigging.md, written to the build folder.
void keepObj(const QuadTestMesh& m, const std::string& name) {
#ifdef ODESKIN_QUAD_MESH_DIR
  std::error_code ec;
  std::filesystem::create_directories(ODESKIN_QUAD_MESH_DIR, ec);
  const Status s = writeObj(std::filesystem::path(ODESKIN_QUAD_MESH_DIR) / name, m.positions, m.faces);
  EXPECT_TRUE(s.ok()) << s.toString();
#else
  (void)m;
  (void)name;
#endif
}

// The rig's mode (curve_skeleton_loops.cpp): the test at a few vertices of each edge loop.
constexpr int kSamples = 3;
RayFanOptions sampledOptions() {
  RayFanOptions options;
  options.loop_samples = kSamples;
  return options;
}

// The rig's mode on a swept tube: edges classified as well as by the full test from under a
// quarter of the vertices, and the `rings` rings and `lines` lines the full test finds.
void expectSampledLike(const char* name, const QuadTestMesh& m, const PolyMesh& mesh, std::size_t rings, std::size_t lines) {
  const RayFanDirections sampled = rayFanDirections(mesh, sampledOptions());
  const Accuracy s = ringAccuracy(m, mesh, sampled);
  std::printf("%s, %d per loop: %zu of %zu vertices tested, %.2f%% of %zu edges right\n", name, kSamples,
              sampled.tested_vertices, m.positions.size(), 100.0 * s.fraction(), s.known);
  EXPECT_GE(s.fraction(), 0.98) << name;
  EXPECT_LT(sampled.tested_vertices, m.positions.size() / 4) << name;
  const DirectedLoops sampled_loops = directedEdgeLoops(mesh, sampled, 6);
  EXPECT_EQ(sampled_loops.rings.size(), rings) << name;
  EXPECT_EQ(sampled_loops.axial.size(), lines) << name;
}

TEST(RayFanDirections, CapsuleEdgesAndRings) {
  const QuadTestMesh m = testing::quadCapsule(6.0, 0.5, 24);
  const PolyMesh mesh = polyMesh(m);
  const RayFanDirections d = rayFanDirections(mesh);
  const Accuracy a = ringAccuracy(m, mesh, d);
  std::printf("capsule: %zu vertices, %zu of %zu measured, %.2f%% of %zu edges right\n", m.positions.size(), d.measured_vertices,
              m.positions.size(), 100.0 * a.fraction(), a.known);
  EXPECT_GE(a.fraction(), 0.98);
  // The ray of a tube's vertex meets the opposite wall: the diameter.
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    if (m.ring[i] >= 0 && d.diameters[i] > 0.0 && std::abs(m.positions[i].x - 3.0) < 2.0) {
      EXPECT_NEAR(d.diameters[i], 1.0, 0.02);
    }
  }
  // Every ring of the sweep is a closed circumferential loop but the two next to the poles (their
  // vertices touch triangles, where a walk has no straight on); the meridians are axial.
  const DirectedLoops loops = directedEdgeLoops(mesh, d, 6);
  int rings = 0;
  for (int r : m.ring) rings = std::max(rings, r + 1);
  std::printf("capsule: %zu rings of %d, %zu lines along it\n", loops.rings.size(), rings, loops.axial.size());
  EXPECT_EQ(loops.rings.size(), static_cast<std::size_t>(rings - 2));
  for (const EdgeLoop& loop : loops.rings) {
    ASSERT_FALSE(loop.vertices.empty());
    for (const std::uint32_t v : loop.vertices) EXPECT_EQ(m.ring[v], m.ring[loop.vertices.front()]);
  }
  EXPECT_EQ(loops.axial.size(), 24u);
  // Tested only at a few vertices per loop (the rig's mode): the same classes and loops.
  expectSampledLike("capsule", m, mesh, loops.rings.size(), loops.axial.size());
}

TEST(RayFanDirections, BentTubeEdgesAndRings) {
  const QuadTestMesh m = testing::bentTube(3.0, 3.0, 1.0, 0.4, 24);
  const PolyMesh mesh = polyMesh(m);
  for (const bool full_fan : {true, false}) {
    RayFanOptions options;
    options.full_fan = full_fan;
    const RayFanDirections fanned = rayFanDirections(mesh, options);
    const Accuracy a = ringAccuracy(m, mesh, fanned);
    std::printf("bent tube, %s: %zu vertices, %zu measured, %.2f%% of %zu edges right\n", full_fan ? "full fan" : "edge planes first",
                m.positions.size(), fanned.measured_vertices, 100.0 * a.fraction(), a.known);
    EXPECT_GE(a.fraction(), 0.98);
  }
  const RayFanDirections d = rayFanDirections(mesh);
  const DirectedLoops loops = directedEdgeLoops(mesh, d, 6);
  int rings = 0;
  for (int r : m.ring) rings = std::max(rings, r + 1);
  std::printf("bent tube: %zu rings of %d, %zu lines along it\n", loops.rings.size(), rings, loops.axial.size());
  // Every ring of the open tube closes (boundary vertices of valence 3 walk along the rims).
  EXPECT_EQ(loops.rings.size(), static_cast<std::size_t>(rings));
  EXPECT_EQ(loops.axial.size(), 24u);
  expectSampledLike("bent tube", m, mesh, static_cast<std::size_t>(rings), 24u);
}

TEST(RayFanDirections, SubdividedTShape) {
  const QuadTestMesh m = testing::quadT(4, 6, 3);
  const PolyMesh mesh = polyMesh(m);
  for (const bool full_fan : {true, false}) {
    RayFanOptions options;
    options.full_fan = full_fan;
    const RayFanDirections d = rayFanDirections(mesh, options);
    const Accuracy a = axisAccuracy(m, mesh, d);
    std::printf("T, %s: %zu vertices, %zu measured, %.2f%% of %zu edges in the arms right, %zu undecided\n",
                full_fan ? "full fan" : "edge planes first", m.positions.size(), d.measured_vertices, 100.0 * a.fraction(),
                a.known, d.unknown_edges);
    EXPECT_GE(a.fraction(), 0.95);
    const DirectedLoops loops = directedEdgeLoops(mesh, d, 6);
    std::printf("T: %zu rings, %zu lines\n", loops.rings.size(), loops.axial.size());
    EXPECT_GT(loops.rings.size(), 20u);
  }
  const RayFanDirections full = rayFanDirections(mesh);
  const RayFanDirections sampled = rayFanDirections(mesh, sampledOptions());
  const Accuracy s = axisAccuracy(m, mesh, sampled);
  const DirectedLoops full_loops = directedEdgeLoops(mesh, full, 6);
  const DirectedLoops sampled_loops = directedEdgeLoops(mesh, sampled, 6);
  std::printf("T, %d per loop: %zu of %zu vertices tested, %.2f%% of %zu edges in the arms right, %zu undecided; %zu rings, %zu lines\n",
              kSamples, sampled.tested_vertices, m.positions.size(), 100.0 * s.fraction(), s.known, sampled.unknown_edges,
              sampled_loops.rings.size(), sampled_loops.axial.size());
  EXPECT_GE(s.fraction(), 0.95);
  EXPECT_LT(sampled.tested_vertices, m.positions.size() / 4);
  EXPECT_EQ(sampled_loops.rings.size(), full_loops.rings.size());
}

TEST(RayFanDirections, CatmullClarkCatIsClassified) {
  // A real character made all quads by one Catmull-Clark step: no ground truth, but every vertex
  // must be handled and most edges get a class. It has no closed straight loops (every old vertex
  // of valence 6 and every triangle centre of valence 3 ends a walk), so no rings are asked for.
  Result<ObjMesh> cat = readObj(std::string(ODESKIN_DATA_DIR) + "/cat-poses/cat-00.obj");
  ASSERT_TRUE(cat.ok()) << cat.status().toString();
  const QuadTestMesh m = testing::catmullClark(cat->positions, cat->faces, 1);
  const PolyMesh mesh = polyMesh(m);
  const auto start = std::chrono::steady_clock::now();
  const RayFanDirections d = rayFanDirections(mesh);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const DirectedLoops loops = directedEdgeLoops(mesh, d, 6);
  std::printf("cat, one Catmull-Clark step: %zu vertices, %zu measured, edges %zu circumferential %zu axial %zu undecided, "
              "%zu rings, %.1f ms\n",
              m.positions.size(), d.measured_vertices, d.circumferential_edges, d.axial_edges, d.unknown_edges,
              loops.rings.size(), 1e3 * seconds);
  EXPECT_GE(static_cast<double>(d.measured_vertices), 0.7 * static_cast<double>(m.positions.size()));
  EXPECT_LE(static_cast<double>(d.unknown_edges), 0.1 * static_cast<double>(mesh.n_edges()));
}

TEST(RayFanDirections, EmptyAndFlatMeshesAreHandled) {
  PolyMesh empty;
  const RayFanDirections none = rayFanDirections(empty);
  EXPECT_EQ(none.measured_vertices, 0u);
  // A flat grid of quads has no opposite wall: nothing is measured, every edge undecided.
  QuadTestMesh grid;
  for (int j = 0; j < 5; ++j) {
    for (int i = 0; i < 5; ++i) grid.positions.push_back(Vec3(i, j, 0.0));
  }
  for (std::uint32_t j = 0; j < 4; ++j) {
    for (std::uint32_t i = 0; i < 4; ++i) grid.face({j * 5 + i, j * 5 + i + 1, (j + 1) * 5 + i + 1, (j + 1) * 5 + i});
  }
  const PolyMesh mesh = polyMesh(grid);
  const RayFanDirections d = rayFanDirections(mesh);
  EXPECT_EQ(d.measured_vertices, 0u);
  EXPECT_EQ(d.unknown_edges, mesh.n_edges());
  EXPECT_TRUE(directedEdgeLoops(mesh, d, 3).rings.empty());
  // Sampled per loop: every vertex of every loop is tried (none gets an axis), nothing decided;
  // a sample count above the loop lengths is the same.
  for (const int samples : {3, 1000000}) {
    RayFanOptions options;
    options.loop_samples = samples;
    const RayFanDirections sampled = rayFanDirections(mesh, options);
    EXPECT_EQ(sampled.tested_vertices, grid.positions.size());
    EXPECT_EQ(sampled.measured_vertices, 0u);
    EXPECT_EQ(sampled.unknown_edges, mesh.n_edges());
    EXPECT_TRUE(directedEdgeLoops(mesh, sampled, 3).rings.empty());
  }
  RayFanOptions options;
  options.loop_samples = 3;
  EXPECT_EQ(rayFanDirections(empty, options).tested_vertices, 0u);
}

TEST(RayFanRig, BentTubeGetsAnElbowJoint) {
  // Arms of different lengths, so that the root (the middle of the body) is not at the elbow.
  const QuadTestMesh m = testing::bentTube(2.0, 4.5, 1.0, 0.4, 24);
  keepObj(m, "bent-tube.obj");
  CurveRigOptions options;
  options.animation.template_kind = SkeletonTemplateKind::kNone;
  Result<CurveRig> rig = buildCurveRig(m.positions, m.faces, {}, options);
  ASSERT_TRUE(rig.ok()) << rig.status().toString();
  EXPECT_EQ(rig->curve_skeleton.source, CurveSource::kEdgeLoops) << rig->curve_skeleton.note;
  const Vec3 elbow(std::sin(0.25 * std::numbers::pi), 1.0 - std::cos(0.25 * std::numbers::pi), 0.0);
  double nearest = 1e300;
  const AnimationSkeleton& a = rig->animation;
  for (std::size_t j = 0; j < a.jointCount(); ++j) {
    if (a.reasons[j] == JointReason::kBend) nearest = std::min(nearest, glm::length(a.joints[j] - elbow));
  }
  std::printf("bent tube rig: %zu bones, %zu curves, nearest bend joint %.3f from the elbow (diagonal %.2f), curves %.2f ms\n",
              rig->rig.skeleton.boneCount(), rig->curve_skeleton.curves.size(), nearest, visual::boundsOf(m.positions).diagonal(),
              1e3 * rig->seconds_curves);
  EXPECT_LT(nearest, 0.05 * visual::boundsOf(m.positions).diagonal());
  // The levels, asked for, give a joint there too: the loops agree with them.
  options.curves.source = CurveSource::kLevels;
  Result<CurveRig> levels = buildCurveRig(m.positions, m.faces, {}, options);
  ASSERT_TRUE(levels.ok());
  EXPECT_EQ(levels->curve_skeleton.source, CurveSource::kLevels);
}

TEST(RayFanRig, TShapeGetsAJunction) {
  const QuadTestMesh m = testing::quadT(4, 6, 3);
  keepObj(m, "t-shape.obj");
  CurveRigOptions options;
  options.animation.template_kind = SkeletonTemplateKind::kNone;
  Result<CurveRig> rig = buildCurveRig(m.positions, m.faces, {}, options);
  ASSERT_TRUE(rig.ok()) << rig.status().toString();
  EXPECT_EQ(rig->curve_skeleton.source, CurveSource::kEdgeLoops) << rig->curve_skeleton.note;
  const CurveSkeleton& s = rig->curve_skeleton.skeleton;
  std::size_t junctions = 0;
  double nearest = 1e300;
  for (std::size_t n = 0; n < s.nodeCount(); ++n) {
    if (s.kinds[n] != SkeletonNodeKind::kJunction && s.kinds[n] != SkeletonNodeKind::kRoot) continue;
    junctions += s.kinds[n] == SkeletonNodeKind::kJunction ? 1 : 0;
    nearest = std::min(nearest, glm::length(s.positions[n] - Vec3(0.0, 0.3, 0.5)));
  }
  std::printf("T rig: %zu bones, %zu curves, %zu junctions, junction or root %.3f from the T's centre\n",
              rig->rig.skeleton.boneCount(), rig->curve_skeleton.curves.size(), junctions, nearest);
  EXPECT_LT(nearest, 1.0);
  EXPECT_GE(rig->rig.skeleton.boneCount(), 3u);
}

TEST(RayFanRig, TimingOnSevenThousandVertices) {
  // A bent tube of ~7,000 vertices (48 sides): the thesis's cat has 7,207. Best of 5.
  const QuadTestMesh m = testing::bentTube(3.0, 3.0, 1.0, 0.4, 48);
  keepObj(m, "bent-tube-7k.obj");
  CurveRigOptions options;
  options.compute_weights = false;
  double curves = 1e300, skeleton = 1e300;
  for (int run = 0; run < 5; ++run) {
    Result<CurveRig> rig = buildCurveRig(m.positions, m.faces, {}, options);
    ASSERT_TRUE(rig.ok()) << rig.status().toString();
    ASSERT_EQ(rig->curve_skeleton.source, CurveSource::kEdgeLoops);
    curves = std::min(curves, rig->seconds_curves);
    skeleton = std::min(skeleton, rig->seconds_skeleton);
  }
  std::printf("bent tube %zu vertices: curves (vertex identification) %.2f ms, skeleton %.3f ms (best of 5)\n",
              m.positions.size(), 1e3 * curves, 1e3 * skeleton);
  EXPECT_GT(m.positions.size(), 6500u);
}

}  // namespace
}  // namespace odeskin
