// SPDX-License-Identifier: MIT
// The iso-curve builder's pruned searches against plain scans, on real meshes and rigs: plane cuts
// with and without each region's bounding-box tree, bindings with the pruned and the exhaustive
// search, the cut mesh's neighbours and the vertex adjacency against straightforward rebuilds.
// Every comparison is exact: the pruning only skips what cannot change the answer.
#include <algorithm>
#include <array>
#include <cstdio>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "engine/curves/curve_orientation.hpp"
#include "engine/curves/part_planes.hpp"
#include "engine/curves/part_segmentation.hpp"
#include "engine/curves/plane_cuts.hpp"
#include "engine/curves/vertex_binding.hpp"
#include "engine/io/libigl_io.hpp"
#include "engine/io/obj_reader.hpp"
#include "engine/mesh/adjacency.hpp"
#include "engine/mesh/face_fans.hpp"
#include "engine/mesh/poly_mesh.hpp"
#include "engine/rig/auto_rig.hpp"

namespace odeskin {
namespace {

const std::string kData = ODESKIN_DATA_DIR;

struct Rigged {
  std::string name;
  std::vector<Vec3> rest;
  FaceList faces;
  Skeleton skeleton;
  Influences influences;
};

// Two poses and the automatic rig (what the pipeline gives the curve builder for OBJ input).
Rigged autoRigged(const std::string& name, const std::string& a, const std::string& b) {
  const std::vector<std::filesystem::path> paths = {kData + a, kData + b};
  Result<ExampleSet> ex = readObjSequence(paths);
  EXPECT_TRUE(ex.ok()) << ex.status().toString();
  Rigged r{name, ex->rest_positions, ex->faces, {}, {}};
  Result<Rig> rig = autoRig(ex->rest_positions, ex->faces, ex->poses);
  EXPECT_TRUE(rig.ok()) << rig.status().toString();
  r.skeleton = rig->skeleton;
  r.influences = rig->influences;
  return r;
}

Rigged cheburashka() {
  Result<ObjMesh> obj = readObj(kData + "/cheburashka/cheburashka.obj");
  EXPECT_TRUE(obj.ok()) << obj.status().toString();
  Rigged r{"cheburashka (its own rig)", obj->positions, obj->faces, {}, {}};
  Result<Skeleton> skeleton = readTgf(kData + "/cheburashka/cheburashka.tgf");
  EXPECT_TRUE(skeleton.ok());
  r.skeleton = *skeleton;
  Result<Influences> weights =
      readWeightsDmat(kData + "/cheburashka/cheburashka.DMAT", r.rest.size(), r.skeleton.boneCount());
  EXPECT_TRUE(weights.ok()) << weights.status().toString();
  r.influences = *weights;
  return r;
}

const std::vector<Rigged>& datasets() {
  static const std::vector<Rigged> all = {
      autoRigged("cat-poses 00-01", "/cat-poses/cat-00.obj", "/cat-poses/cat-01.obj"),
      autoRigged("horse-gallop 01, 09 (two holes)", "/horse-gallop/horse-01.obj", "/horse-gallop/horse-09.obj"),
      cheburashka()};
  return all;
}

void expectSameLayout(const CurveLayout& a, const CurveLayout& b, const std::string& what) {
  ASSERT_EQ(a.curves.size(), b.curves.size()) << what;
  for (std::size_t c = 0; c < a.curves.size(); ++c) {
    const CurveDraft& x = a.curves[c];
    const CurveDraft& y = b.curves[c];
    ASSERT_EQ(x.points.size(), y.points.size()) << what << " curve " << c;
    EXPECT_EQ(x.closed, y.closed) << what << " curve " << c;
    for (std::size_t j = 0; j < x.points.size(); ++j) {
      EXPECT_EQ(x.points[j].a, y.points[j].a) << what << " curve " << c << " point " << j;
      EXPECT_EQ(x.points[j].b, y.points[j].b) << what << " curve " << c << " point " << j;
      EXPECT_EQ(x.points[j].t, y.points[j].t) << what << " curve " << c << " point " << j;
    }
  }
  ASSERT_EQ(a.sequences.size(), b.sequences.size()) << what;
  for (std::size_t p = 0; p < a.sequences.size(); ++p) {
    ASSERT_EQ(a.sequences[p].size(), b.sequences[p].size()) << what << " part " << p;
    for (std::size_t k = 0; k < a.sequences[p].size(); ++k) {
      EXPECT_EQ(a.sequences[p][k].curve, b.sequences[p][k].curve) << what;
      EXPECT_EQ(a.sequences[p][k].plane.origin, b.sequences[p][k].plane.origin) << what;
      EXPECT_EQ(a.sequences[p][k].plane.normal, b.sequences[p][k].plane.normal) << what;
    }
  }
}

TEST(CurveSearch, PlaneCutsAndBindingsMatchTheScans) {
  for (const Rigged& d : datasets()) {
    SCOPED_TRACE(d.name);
    ASSERT_TRUE(isSimpleManifold(d.faces, d.rest.size()));
    const VertexAdjacency adjacency = vertexAdjacency(d.faces, d.rest.size());
    const double spacing = 3.0 * meanEdgeLength(d.rest, adjacency);
    const Segmentation seg = segmentParts(d.rest, adjacency, d.skeleton, d.influences, 16, 4);
    const CutMesh mesh = buildCutMesh(d.faces, d.rest.size());
    // Every region with a tree from the start, none with one, and the default (after a few cuts).
    CurveLayout layouts[3];
    const std::size_t thresholds[3] = {0, std::numeric_limits<std::size_t>::max(), CutRegion::kScansBeforeTree};
    for (int k = 0; k < 3; ++k) {
      layouts[k] = planeCutCurves(d.rest, mesh, adjacency, seg, {spacing, 0.25, 8, thresholds[k]});
      addBoundaryLoops(d.rest, boundaryLoopsOfFaces(d.faces, d.rest.size()), seg, spacing, 8, layouts[k]);
    }
    expectSameLayout(layouts[0], layouts[1], "trees everywhere vs scans");
    expectSameLayout(layouts[2], layouts[1], "default vs scans");
    CurveLayout& layout = layouts[2];
    orientCurves(d.rest, seg, layout);
    compactCurves(layout);
    ASSERT_GT(layout.curves.size(), 10u);

    const std::vector<CurveBinding> pruned = bindVertices(d.rest, adjacency, seg, layout, spacing);
    const std::vector<CurveBinding> treed = bindVertices(d.rest, adjacency, seg, layout, spacing, BindingSearch::kPrunedTrees);
    const std::vector<CurveBinding> scanned =
        bindVertices(d.rest, adjacency, seg, layout, spacing, BindingSearch::kExhaustive);
    ASSERT_EQ(pruned.size(), scanned.size());
    ASSERT_EQ(treed.size(), scanned.size());
    std::size_t blended = 0;
    for (std::size_t i = 0; i < pruned.size(); ++i) {
      for (const auto* search : {&pruned, &treed}) {
        const CurveBinding& b = (*search)[i];
        const char* what = search == &pruned ? "balls, vertex " : "trees, vertex ";
        EXPECT_EQ(b.curve_a, scanned[i].curve_a) << what << i;
        EXPECT_EQ(b.curve_b, scanned[i].curve_b) << what << i;
        EXPECT_EQ(b.w, scanned[i].w) << what << i;
        EXPECT_EQ(b.v, scanned[i].v) << what << i;
      }
      blended += pruned[i].curve_a != pruned[i].curve_b ? 1 : 0;
    }
    std::printf("%s: %zu curves, %zu of %zu vertices between two curves, all bound as the scans bind them\n",
                d.name.c_str(), layout.curves.size(), blended, pruned.size());
    EXPECT_GT(blended, pruned.size() / 3);  // the comparison covers many blended vertices
  }
}

TEST(CurveSearch, RegionTreeFindsEveryCrossedTriangle) {
  const Rigged& d = datasets().front();
  const CutMesh mesh = buildCutMesh(d.faces, d.rest.size());
  std::vector<std::uint32_t> all(mesh.triangles.size());
  for (std::uint32_t t = 0; t < all.size(); ++t) all[t] = t;
  const CutRegion region(mesh, d.rest, all, 0);
  ASSERT_TRUE(region.indexed());
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::size_t crossed_total = 0, near_total = 0;
  for (int k = 0; k < 200; ++k) {
    const Vec3 normal = glm::normalize(Vec3(unit(rng), unit(rng), unit(rng)));
    const Plane plane{d.rest[rng() % d.rest.size()], normal};
    std::vector<std::uint32_t> near;
    region.nearPlane(plane, near);
    std::vector<char> found(mesh.triangles.size(), 0);
    for (std::uint32_t t : near) found[t] = 1;
    for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) {
      int front = 0;
      for (std::uint32_t v : mesh.triangles[t]) front += glm::dot(normal, d.rest[v] - plane.origin) >= 0.0 ? 1 : 0;
      if (front == 0 || front == 3) continue;
      ++crossed_total;
      EXPECT_TRUE(found[t]) << "plane " << k << " crosses triangle " << t << " outside the tree's answer";
    }
    near_total += near.size();
  }
  std::printf("200 planes through the cat: %zu crossed triangles, the tree returned %zu\n", crossed_total, near_total);
  EXPECT_LT(near_total, 4 * crossed_total);  // it prunes: far fewer than 200 x all triangles
}

TEST(CurveSearch, CutMeshNeighboursAndAdjacencyMatchStraightRebuilds) {
  for (const Rigged& d : datasets()) {
    SCOPED_TRACE(d.name);
    const CutMesh mesh = buildCutMesh(d.faces, d.rest.size());
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> owner;
    for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) {
      for (int k = 0; k < 3; ++k) owner[{mesh.triangles[t][k], mesh.triangles[t][(k + 1) % 3]}] = t;
    }
    for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) {
      for (int k = 0; k < 3; ++k) {
        const auto it = owner.find({mesh.triangles[t][(k + 1) % 3], mesh.triangles[t][k]});
        const std::int32_t expected = it == owner.end() ? -1 : static_cast<std::int32_t>(it->second);
        ASSERT_EQ(mesh.neighbours[t][k], expected) << "triangle " << t << " edge " << k;
      }
    }
    const VertexAdjacency adjacency = vertexAdjacency(d.faces, d.rest.size());
    std::vector<std::vector<std::uint32_t>> rows(d.rest.size());
    for (std::size_t f = 0; f < d.faces.faceCount(); ++f) {
      const std::uint32_t begin = d.faces.face_offsets[f];
      const std::uint32_t n = d.faces.face_offsets[f + 1] - begin;
      for (std::uint32_t k = 0; k < n; ++k) {
        rows[d.faces.indices[begin + k]].push_back(d.faces.indices[begin + (k + 1) % n]);
        rows[d.faces.indices[begin + (k + 1) % n]].push_back(d.faces.indices[begin + k]);
      }
    }
    ASSERT_EQ(adjacency.offsets.size(), d.rest.size() + 1);
    for (std::uint32_t i = 0; i < d.rest.size(); ++i) {
      std::sort(rows[i].begin(), rows[i].end());
      rows[i].erase(std::unique(rows[i].begin(), rows[i].end()), rows[i].end());
      const auto of = adjacency.of(i);
      ASSERT_EQ(std::vector<std::uint32_t>(of.begin(), of.end()), rows[i]) << "vertex " << i;
    }
  }
}

}  // namespace
}  // namespace odeskin
