// SPDX-License-Identifier: MIT
#include "engine/curves/iso_curves.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <numbers>
#include <set>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "engine/io/obj_reader.hpp"
#include "engine/mesh/poly_mesh.hpp"
#include "engine/offline/fourier_fit.hpp"

namespace odeskin {
namespace {

const std::string kData = ODESKIN_DATA_DIR;
constexpr double kPi = std::numbers::pi;

struct Mesh {
  std::vector<Vec3> positions;
  FaceList faces;
};

void addFace(FaceList& faces, std::initializer_list<std::uint32_t> corners) {
  faces.indices.insert(faces.indices.end(), corners);
  faces.face_offsets.push_back(static_cast<std::uint32_t>(faces.indices.size()));
}

// Open tube along +x: `rings` rings of `segments` vertices, ring r at x = r * length / (rings - 1),
// vertex s at angle 2 pi s / segments in the yz plane. Quads, or each quad split in two.
Mesh tube(std::uint32_t rings, std::uint32_t segments, double length, double radius, bool quads) {
  Mesh m;
  for (std::uint32_t r = 0; r < rings; ++r) {
    for (std::uint32_t s = 0; s < segments; ++s) {
      const double a = 2.0 * kPi * s / segments;
      m.positions.push_back({length * r / (rings - 1), radius * std::cos(a), radius * std::sin(a)});
    }
  }
  for (std::uint32_t r = 0; r + 1 < rings; ++r) {
    for (std::uint32_t s = 0; s < segments; ++s) {
      const std::uint32_t a = r * segments + s, b = r * segments + (s + 1) % segments;
      const std::uint32_t c = b + segments, d = a + segments;
      if (quads) {
        addFace(m.faces, {a, b, c, d});
      } else {
        addFace(m.faces, {a, b, c});
        addFace(m.faces, {a, c, d});
      }
    }
  }
  return m;
}

// The surface of a union of unit voxels (quads facing out, split in two triangles).
Mesh voxelSurface(const std::set<std::array<int, 3>>& voxels) {
  Mesh m;
  std::map<std::array<int, 3>, std::uint32_t> index;
  auto vertex = [&](std::array<int, 3> p) {
    auto [it, added] = index.emplace(p, static_cast<std::uint32_t>(m.positions.size()));
    if (added) m.positions.push_back({p[0], p[1], p[2]});
    return it->second;
  };
  for (const auto& v : voxels) {
    for (int axis = 0; axis < 3; ++axis) {
      for (int sign : {-1, 1}) {
        std::array<int, 3> n = v;
        n[axis] += sign;
        if (voxels.count(n)) continue;
        const int u = (axis + 1) % 3, w = (axis + 2) % 3;
        std::array<int, 3> base = v;
        base[axis] += sign > 0 ? 1 : 0;
        std::array<std::uint32_t, 4> q;
        const int du[4] = {0, 1, 1, 0}, dw[4] = {0, 0, 1, 1};
        for (int k = 0; k < 4; ++k) {
          std::array<int, 3> p = base;
          p[u] += du[k];
          p[w] += dw[k];
          q[k] = vertex(p);
        }
        if (sign < 0) std::swap(q[1], q[3]);
        addFace(m.faces, {q[0], q[1], q[2]});
        addFace(m.faces, {q[0], q[2], q[3]});
      }
    }
  }
  return m;
}

Skeleton skeletonOf(const std::vector<std::pair<Vec3, Vec3>>& bones, std::vector<std::int32_t> parents) {
  Skeleton s;
  for (const auto& [head, tail] : bones) {
    s.heads.push_back(head);
    s.tails.push_back(tail);
    s.names.push_back("");
  }
  s.parents = std::move(parents);
  return s;
}

double segmentDistance(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double t = std::clamp(glm::dot(p - a, ab) / glm::dot(ab, ab), 0.0, 1.0);
  return glm::length(a + t * ab - p);
}

// Test-local rig weights: each vertex wholly on its nearest bone segment.
Influences nearestBoneWeights(std::span<const Vec3> positions, const Skeleton& skeleton) {
  Influences in;
  for (const Vec3& p : positions) {
    std::uint32_t best = 0;
    for (std::uint32_t b = 1; b < skeleton.boneCount(); ++b) {
      if (segmentDistance(p, skeleton.heads[b], skeleton.tails[b]) <
          segmentDistance(p, skeleton.heads[best], skeleton.tails[best])) {
        best = b;
      }
    }
    in.bones.push_back(best);
    in.weights.push_back(1.0);
    in.offsets.push_back(static_cast<std::uint32_t>(in.bones.size()));
  }
  return in;
}

// libigl ASCII .DMAT (README: "cols rows", then column-major values) as V x B weights.
Influences readDmatWeights(const std::string& path) {
  std::ifstream file(path);
  std::size_t cols = 0, rows = 0;
  file >> cols >> rows;
  std::vector<double> values(cols * rows);
  for (double& x : values) file >> x;
  EXPECT_TRUE(file) << path;
  std::vector<double> dense(rows * cols);
  for (std::size_t c = 0; c < cols; ++c) {
    for (std::size_t r = 0; r < rows; ++r) dense[r * cols + c] = values[c * rows + r];
  }
  return influencesFromDense(dense, rows, static_cast<std::uint32_t>(cols));
}

// libigl .tgf: joints, '#', bones (start end, 1-based), '#'. Parent: the bone ending at its start.
Skeleton readTgf(const std::string& path) {
  std::ifstream file(path);
  std::string line;
  std::vector<Vec3> joints;
  std::vector<std::pair<int, int>> edges;
  int section = 0;
  while (std::getline(file, line)) {
    if (line.find('#') != std::string::npos) {
      ++section;
      continue;
    }
    std::istringstream in(line);
    if (section == 0) {
      int index = 0;
      Vec3 p;
      if (in >> index >> p.x >> p.y >> p.z) joints.push_back(p);
    } else if (section == 1) {
      int a = 0, b = 0;
      if (in >> a >> b) edges.push_back({a - 1, b - 1});
    }
  }
  std::vector<std::pair<Vec3, Vec3>> bones;
  std::vector<std::int32_t> parents;
  for (const auto& [a, b] : edges) {
    bones.push_back({joints[static_cast<std::size_t>(a)], joints[static_cast<std::size_t>(b)]});
    std::int32_t parent = -1;
    for (std::size_t k = 0; k < edges.size(); ++k) {
      if (edges[k].second == a) parent = static_cast<std::int32_t>(k);
    }
    parents.push_back(parent);
  }
  return skeletonOf(bones, parents);
}

Mesh loadObj(const std::string& path) {
  Result<ObjMesh> obj = readObj(path);
  EXPECT_TRUE(obj.ok()) << obj.status().toString();
  if (!obj.ok()) return {};
  return {obj->positions, obj->faces};
}

struct Summary {
  std::size_t curves = 0;
  std::size_t closed = 0;
  std::size_t paired = 0;  // vertices between two different curves
  std::set<std::uint32_t> parts;
};

// The contract every result must meet: validateCurveSet, every curve >= min_points points with
// strictly increasing v (closed: from 0, below 1; open: 0 to 1), every vertex on existing curves.
Summary expectWellFormed(const CurveSet& set, std::size_t vertex_count, int min_points = 8) {
  const Status valid = validateCurveSet(set, vertex_count);
  EXPECT_TRUE(valid.ok()) << valid.toString();
  EXPECT_EQ(set.bindings.size(), vertex_count);
  EXPECT_EQ(set.vertex_parts.size(), vertex_count);
  Summary s;
  s.curves = set.curves.size();
  for (std::size_t c = 0; c < set.curves.size(); ++c) {
    const IsoCurve& curve = set.curves[c];
    EXPECT_GE(curve.points.size(), static_cast<std::size_t>(min_points)) << "curve " << c;
    EXPECT_EQ(curve.v.size(), curve.points.size());
    if (curve.v.size() != curve.points.size() || curve.v.empty()) continue;
    EXPECT_EQ(curve.v.front(), 0.0) << "curve " << c;
    for (std::size_t j = 1; j < curve.v.size(); ++j) EXPECT_GT(curve.v[j], curve.v[j - 1]) << "curve " << c << " point " << j;
    if (curve.closed) {
      EXPECT_LT(curve.v.back(), 1.0) << "curve " << c;
    } else {
      EXPECT_EQ(curve.v.back(), 1.0) << "curve " << c;
    }
    s.closed += curve.closed ? 1 : 0;
    s.parts.insert(curve.part);
  }
  for (const CurveBinding& b : set.bindings) {
    EXPECT_LT(b.curve_a, set.curves.size());
    EXPECT_LT(b.curve_b, set.curves.size());
    s.paired += b.curve_a != b.curve_b ? 1 : 0;
  }
  return s;
}

double wrap(double x) { return x - std::round(x); }  // to [-0.5, 0.5]

TEST(IsoCurves, RejectsBadInput) {
  const Mesh m = tube(5, 12, 2.0, 0.5, false);
  const Skeleton sk = skeletonOf({{{0, 0, 0}, {2, 0, 0}}}, {-1});
  const Influences in = nearestBoneWeights(m.positions, sk);
  EXPECT_TRUE(buildIsoCurves(m.positions, m.faces, sk, in).ok());

  Influences short_in = in;
  short_in.offsets.pop_back();
  EXPECT_EQ(buildIsoCurves(m.positions, m.faces, sk, short_in).status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(buildIsoCurves(m.positions, m.faces, Skeleton{}, in).status().code(), StatusCode::kInvalidArgument);
  Skeleton no_tails = sk;
  no_tails.tails.clear();
  EXPECT_EQ(buildIsoCurves(m.positions, m.faces, no_tails, in).status().code(), StatusCode::kInvalidArgument);
  CurveOptions o;
  o.snap_threshold = 0.5;
  EXPECT_EQ(buildIsoCurves(m.positions, m.faces, sk, in, o).status().code(), StatusCode::kInvalidArgument);
  o = {};
  o.spacing = -1.0;
  EXPECT_EQ(buildIsoCurves(m.positions, m.faces, sk, in, o).status().code(), StatusCode::kInvalidArgument);
  o = {};
  o.min_points = 2;
  EXPECT_EQ(buildIsoCurves(m.positions, m.faces, sk, in, o).status().code(), StatusCode::kInvalidArgument);

  // Finite, but so large that squared lengths overflow: the plane cuts recursed until the stack
  // ran out (SIGSEGV) before the check. A tube 1e150 long still gets its curves.
  std::vector<Vec3> huge = m.positions;
  for (Vec3& p : huge) p *= 1e200;
  const Skeleton huge_sk = skeletonOf({{{0, 0, 0}, {2e200, 0, 0}}}, {-1});
  const Result<CurveSet> too_large = buildIsoCurves(huge, m.faces, huge_sk, in);
  EXPECT_EQ(too_large.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(too_large.status().message().find("iso-curves: the mesh is too large"), std::string::npos)
      << too_large.status().message();
  for (Vec3& p : huge) p *= 1e-50;
  EXPECT_TRUE(buildIsoCurves(huge, m.faces, skeletonOf({{{0, 0, 0}, {2e150, 0, 0}}}, {-1}), in).ok());

  // A third triangle on an edge already shared by two: non-manifold, named.
  Mesh bad = m;
  addFace(bad.faces, {0, 1, 13});
  const Result<CurveSet> nonmanifold = buildIsoCurves(bad.positions, bad.faces, sk, in);
  EXPECT_EQ(nonmanifold.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(nonmanifold.status().message().find("face " + std::to_string(bad.faces.faceCount())), std::string::npos)
      << nonmanifold.status().message();

  // Edge loops need quads.
  o = {};
  o.method = CurveMethod::kEdgeLoops;
  EXPECT_EQ(buildIsoCurves(m.positions, m.faces, sk, in, o).status().code(), StatusCode::kDegenerate);
  // No curve of 8 points fits on a tube with 6 vertices around.
  const Mesh thin = tube(5, 3, 2.0, 0.5, false);
  EXPECT_EQ(buildIsoCurves(thin.positions, thin.faces, sk, nearestBoneWeights(thin.positions, sk)).status().code(),
            StatusCode::kDegenerate);
}

// A flat strip whose only bone points out of its plane: no cut across the bone meets it, so the
// strip's own long axis is cut instead (open curves across the strip).
TEST(IsoCurves, FlatStripWithABoneOutOfItsPlane) {
  Mesh m;
  constexpr std::uint32_t kLong = 30, kWide = 12;
  for (std::uint32_t i = 0; i < kLong; ++i) {
    for (std::uint32_t j = 0; j < kWide; ++j) m.positions.push_back({0.1 * i, 0.1 * j, 0.0});
  }
  for (std::uint32_t i = 0; i + 1 < kLong; ++i) {
    for (std::uint32_t j = 0; j + 1 < kWide; ++j) {
      const std::uint32_t a = i * kWide + j, b = a + kWide;
      addFace(m.faces, {a, b, b + 1});
      addFace(m.faces, {a, b + 1, a + 1});
    }
  }
  const Skeleton sk = skeletonOf({{{1.5, 0.5, 0.0}, {1.5, 0.5, 1.0}}}, {-1});
  Result<CurveSet> set = buildIsoCurves(m.positions, m.faces, sk, nearestBoneWeights(m.positions, sk));
  ASSERT_TRUE(set.ok()) << set.status().toString();
  const Summary s = expectWellFormed(*set, m.positions.size());
  EXPECT_GE(s.curves, 5u);
  EXPECT_EQ(s.closed, 0u);
  for (const IsoCurve& c : set->curves) {
    const Vec3 first = curvePointPosition(m.positions, c.points.front());
    const Vec3 last = curvePointPosition(m.positions, c.points.back());
    EXPECT_NEAR(std::abs(last.y - first.y), 0.1 * (kWide - 1), 1e-9);  // edge to edge across the strip
  }
}

// Two bones along a triangulated tube, weights blending over the middle third.
class TwoBoneTube : public ::testing::Test {
 protected:
  static constexpr std::uint32_t kRings = 25, kSegments = 24;
  static constexpr double kLength = 6.0, kRadius = 1.0;
  void SetUp() override {
    mesh = tube(kRings, kSegments, kLength, kRadius, false);
    skeleton = skeletonOf({{{0, 0, 0}, {3, 0, 0}}, {{3, 0, 0}, {6, 0, 0}}}, {-1, 0});
    for (const Vec3& p : mesh.positions) {
      const double t = std::clamp((p.x - 2.0) / 2.0, 0.0, 1.0);
      const double w1 = t * t * (3.0 - 2.0 * t);
      influences.bones.insert(influences.bones.end(), {0, 1});
      influences.weights.insert(influences.weights.end(), {1.0 - w1, w1});
      influences.offsets.push_back(static_cast<std::uint32_t>(influences.bones.size()));
    }
  }
  Mesh mesh;
  Skeleton skeleton;
  Influences influences;
};

TEST_F(TwoBoneTube, CurvesAreRingsAndBindingsFollowThem) {
  Result<CurveSet> set = buildIsoCurves(mesh.positions, mesh.faces, skeleton, influences);
  ASSERT_TRUE(set.ok()) << set.status().toString();
  const Summary s = expectWellFormed(*set, mesh.positions.size());
  EXPECT_GE(s.curves, 6u);
  EXPECT_EQ(s.closed, s.curves);
  EXPECT_EQ(s.parts, (std::set<std::uint32_t>{0, 1}));

  // Rings: every point at the radius (a chord's midpoint is at R cos(pi / S)) and the curve
  // nearly perpendicular to the axis (snapping moves a point by a quarter edge at most).
  std::vector<double> curve_x;
  for (const IsoCurve& c : set->curves) {
    double lo = 1e9, hi = -1e9, mean = 0.0;
    for (const CurvePoint& p : c.points) {
      const Vec3 x = curvePointPosition(mesh.positions, p);
      const double r = std::hypot(x.y, x.z);
      EXPECT_GE(r, kRadius * std::cos(kPi / kSegments) - 1e-9);
      EXPECT_LE(r, kRadius + 1e-9);
      lo = std::min(lo, x.x);
      hi = std::max(hi, x.x);
      mean += x.x;
    }
    EXPECT_LT(hi - lo, 0.3);
    curve_x.push_back(mean / static_cast<double>(c.points.size()));
  }
  // w: a vertex between two curves sits where w says along the axis; v: its angle, up to one
  // start offset and one sense for the whole tube (neighbouring curves correspond).
  auto angleOf = [](const Vec3& x) { return std::atan2(x.z, x.y) / (2.0 * kPi); };
  auto spread = [&](double sense) {
    double sum = 0.0;
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
      sum += std::abs(wrap(set->bindings[i].v - sense * angleOf(mesh.positions[i]) - set->bindings[0].v));
    }
    return sum;
  };
  const double sense = spread(1.0) < spread(-1.0) ? 1.0 : -1.0;
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    const Vec3& x = mesh.positions[i];
    const CurveBinding& b = set->bindings[i];
    const double expected_x = (1.0 - b.w) * curve_x[b.curve_a] + b.w * curve_x[b.curve_b];
    EXPECT_NEAR(x.x, expected_x, 0.15) << "vertex " << i;
    EXPECT_LT(std::abs(wrap(b.v - sense * angleOf(x) - set->bindings[0].v)), 0.04) << "vertex " << i;
  }
  // Both end rims are curves of their own, so no vertex is left beyond the curves.
  EXPECT_EQ(s.paired, mesh.positions.size());
}

TEST_F(TwoBoneTube, SnapThresholdPutsPointsOnVertices) {
  CurveOptions o;
  o.snap_threshold = 0.0;
  Result<CurveSet> exact = buildIsoCurves(mesh.positions, mesh.faces, skeleton, influences, o);
  o.snap_threshold = 0.45;
  Result<CurveSet> snapped = buildIsoCurves(mesh.positions, mesh.faces, skeleton, influences, o);
  ASSERT_TRUE(exact.ok() && snapped.ok());
  expectWellFormed(*exact, mesh.positions.size());
  expectWellFormed(*snapped, mesh.positions.size());
  auto onVertex = [](const CurveSet& set) {
    std::size_t n = 0, all = 0;
    for (const IsoCurve& c : set.curves) {
      for (const CurvePoint& p : c.points) {
        n += p.a == p.b ? 1 : 0;
        ++all;
        if (p.a != p.b) {
          EXPECT_TRUE(p.t > 0.0 && p.t < 1.0);
        }
      }
    }
    return static_cast<double>(n) / static_cast<double>(all);
  };
  EXPECT_GT(onVertex(*snapped), onVertex(*exact));
}

TEST(IsoCurves, QuadTubeGivesExactlyItsRings) {
  constexpr std::uint32_t kRings = 17, kSegments = 16;
  const Mesh m = tube(kRings, kSegments, 4.0, 1.0, true);
  const Skeleton sk = skeletonOf({{{0, 0, 0}, {2, 0, 0}}, {{2, 0, 0}, {4, 0, 0}}}, {-1, 0});
  const Influences in = nearestBoneWeights(m.positions, sk);
  Result<CurveSet> set = buildIsoCurves(m.positions, m.faces, sk, in);  // kAuto: all quads
  ASSERT_TRUE(set.ok()) << set.status().toString();
  const Summary s = expectWellFormed(*set, m.positions.size());
  ASSERT_EQ(s.curves, kRings);
  ASSERT_EQ(s.closed, kRings);
  std::set<std::uint32_t> rings_seen;
  for (const IsoCurve& c : set->curves) {
    ASSERT_EQ(c.points.size(), kSegments);
    const std::uint32_t ring = c.points[0].a / kSegments;
    rings_seen.insert(ring);
    for (std::size_t j = 0; j < c.points.size(); ++j) {
      EXPECT_EQ(c.points[j].a, c.points[j].b);
      EXPECT_EQ(c.points[j].a / kSegments, ring);
      // Uniform ring: v is the vertex count along it.
      EXPECT_NEAR(c.v[j], static_cast<double>(j) / kSegments, 1e-12);
    }
  }
  EXPECT_EQ(rings_seen.size(), kRings);
  // A vertex on a ring is bound to that ring's curve alone (w = 0 or 1).
  for (std::uint32_t i = 0; i < m.positions.size(); ++i) {
    const CurveBinding& b = set->bindings[i];
    const std::uint32_t curve = b.w < 0.5 ? b.curve_a : b.curve_b;
    EXPECT_LT(std::min(b.w, 1.0 - b.w), 1e-9);
    EXPECT_EQ(set->curves[curve].points[0].a / kSegments, i / kSegments);
  }
  // Plane cuts work on quads too (fanned into triangles).
  CurveOptions o;
  o.method = CurveMethod::kPlaneCuts;
  Result<CurveSet> cut = buildIsoCurves(m.positions, m.faces, sk, in, o);
  ASSERT_TRUE(cut.ok()) << cut.status().toString();
  expectWellFormed(*cut, m.positions.size());
}

// A T of 3 x 3 voxel bars: two arms meeting a stem of two bones. Parts: the arms (two seams
// each, at the same end), the upper stem (three seams: clustering), the lower stem (one seam).
TEST(IsoCurves, BranchingTShape) {
  std::set<std::array<int, 3>> voxels;
  for (int x = 0; x < 21; ++x)
    for (int y = 9; y < 12; ++y)
      for (int z = 0; z < 3; ++z) voxels.insert({x, y, z});
  for (int x = 9; x < 12; ++x)
    for (int y = 0; y < 9; ++y)
      for (int z = 0; z < 3; ++z) voxels.insert({x, y, z});
  const Mesh m = voxelSurface(voxels);
  const Vec3 centre(10.5, 10.5, 1.5);
  const Skeleton sk = skeletonOf({{centre, {0, 10.5, 1.5}},
                                  {centre, {21, 10.5, 1.5}},
                                  {centre, {10.5, 5, 1.5}},
                                  {{10.5, 5, 1.5}, {10.5, 0, 1.5}}},
                                 {-1, -1, -1, 2});
  const Influences in = nearestBoneWeights(m.positions, sk);
  Result<CurveSet> set = buildIsoCurves(m.positions, m.faces, sk, in);
  ASSERT_TRUE(set.ok()) << set.status().toString();
  const Summary s = expectWellFormed(*set, m.positions.size());
  EXPECT_EQ(s.parts, (std::set<std::uint32_t>{0, 1, 2, 3}));
  std::printf("T shape: %zu vertices, %zu curves (%zu closed), %zu vertices between two curves\n",
              m.positions.size(), s.curves, s.closed, s.paired);
  // Curves along the arms and the lower stem run around the bar.
  for (const IsoCurve& c : set->curves) {
    if (c.part == 3) {
      EXPECT_TRUE(c.closed);
    }
  }
  EXPECT_GT(s.paired, m.positions.size() / 2);
}

struct Dataset {
  Mesh mesh;
  Skeleton skeleton;
  Influences influences;
};

Dataset cylinder() {
  Dataset d;
  d.mesh = loadObj(kData + "/cylinder/cylinder.obj");
  // README: joints 1 (0,0,0), 2 (0.9,0,0), 3 (1.8,0,0), 4 (-0.9,0,0), 5 (-1.8,0,0); bones 1->2,
  // 2->3, 1->4, 4->5; parents [-1, 0, -1, 2].
  d.skeleton = skeletonOf({{{0, 0, 0}, {0.9, 0, 0}}, {{0.9, 0, 0}, {1.8, 0, 0}}, {{0, 0, 0}, {-0.9, 0, 0}},
                           {{-0.9, 0, 0}, {-1.8, 0, 0}}},
                          {-1, 0, -1, 2});
  d.influences = readDmatWeights(kData + "/cylinder/cylinder.DMAT");
  return d;
}

TEST(IsoCurvesData, Cylinder) {
  const Dataset d = cylinder();
  ASSERT_EQ(d.mesh.positions.size(), 420u);
  Result<CurveSet> set = buildIsoCurves(d.mesh.positions, d.mesh.faces, d.skeleton, d.influences);
  ASSERT_TRUE(set.ok()) << set.status().toString();
  const Summary s = expectWellFormed(*set, d.mesh.positions.size());
  EXPECT_EQ(s.closed, s.curves);
  EXPECT_EQ(s.parts, (std::set<std::uint32_t>{0, 1, 2, 3}));
  std::printf("cylinder: %zu curves, %zu of 420 vertices between two curves\n", s.curves, s.paired);
}

// Max and RMS over the vertices of |u - ((1 - w) C_a(v) + w C_b(v))|, C fitted to u sampled at
// each curve's points with N = 4 modes; and max |u|.
// (Curves with too few points for N = 4 take the most modes they determine, as the fit does.)
struct FieldError {
  double max = 0.0, rms = 0.0, scale = 0.0;
  std::vector<double> sorted;  // per vertex, ascending
  double quantile(double q) const { return sorted[static_cast<std::size_t>(q * static_cast<double>(sorted.size() - 1))]; }
};
template <typename Field>
FieldError bindingError(const CurveSet& set, std::span<const Vec3> positions, Field field) {
  std::vector<FourierFit> fits;
  for (const IsoCurve& c : set.curves) {
    std::vector<Vec3> values;
    for (const CurvePoint& p : c.points) values.push_back(field(curvePointPosition(positions, p)));
    const int points = static_cast<int>(c.points.size());
    const int modes = std::min(4, c.closed ? (points - 1) / 2 : (points - 2) / 2);
    Result<FourierFit> fit = fitFourier(c.v, values, modes, c.closed);
    EXPECT_TRUE(fit.ok()) << fit.status().toString();
    fits.push_back(fit.ok() ? *fit : FourierFit{});
  }
  FieldError e;
  for (std::size_t i = 0; i < positions.size(); ++i) {
    const CurveBinding& b = set.bindings[i];
    const Vec3 u = field(positions[i]);
    const Vec3 series = (1.0 - b.w) * fits[b.curve_a].evaluate(b.v) + b.w * fits[b.curve_b].evaluate(b.v);
    const double d = glm::length(series - u);
    e.sorted.push_back(d);
    e.max = std::max(e.max, d);
    e.rms += d * d;
    e.scale = std::max(e.scale, glm::length(u));
  }
  e.rms = std::sqrt(e.rms / static_cast<double>(positions.size()));
  std::sort(e.sorted.begin(), e.sorted.end());
  return e;
}

// The curves represent smooth fields. A field linear along the tube (angular modes 1 and 2 at
// each x) is carried by the bindings up to the points' spread about their planes and the v
// mismatch of neighbouring curves; a bend-like field (quadratic in x) adds the error of linear
// blending between curves, at most max|u_xx| g^2 / 8 for the largest gap g between curves.
TEST(IsoCurvesData, CylinderBindingsRepresentSmoothFields) {
  const Dataset d = cylinder();
  Result<CurveSet> set = buildIsoCurves(d.mesh.positions, d.mesh.faces, d.skeleton, d.influences);
  ASSERT_TRUE(set.ok()) << set.status().toString();
  const FieldError linear = bindingError(*set, d.mesh.positions, [](const Vec3& p) {
    return Vec3(-0.3 * p.x * p.y, 0.3 * p.x + 0.2 * p.y * p.z, 0.1 * p.x * p.z);
  });
  const FieldError bend = bindingError(*set, d.mesh.positions, [](const Vec3& p) {
    return Vec3(-0.3 * p.x * p.y, 0.15 * p.x * p.x, 0.1 * p.x * p.z);
  });
  std::vector<double> xs;
  for (const IsoCurve& c : set->curves) {
    double x = 0.0;
    for (const CurvePoint& p : c.points) x += curvePointPosition(d.mesh.positions, p).x;
    xs.push_back(x / static_cast<double>(c.points.size()));
  }
  std::sort(xs.begin(), xs.end());
  double gap = 0.0;
  for (std::size_t k = 1; k < xs.size(); ++k) gap = std::max(gap, xs[k] - xs[k - 1]);
  const double blend_bound = 0.3 * gap * gap / 8.0;
  std::printf("cylinder fields: linear max %.5f rms %.5f (max |u| %.3f); bend max %.4f rms %.4f (max |u| %.3f, "
              "largest gap %.3f, blending bound %.4f)\n",
              linear.max, linear.rms, linear.scale, bend.max, bend.rms, bend.scale, gap, blend_bound);
  EXPECT_LT(linear.max, 0.005 * linear.scale);
  EXPECT_LT(bend.max, blend_bound + 0.01 * bend.scale);
  EXPECT_LT(bend.rms, 0.5 * blend_bound + 0.005 * bend.scale);
}

Dataset cat() {
  Dataset d;
  d.mesh = loadObj(kData + "/cat-poses/cat-00.obj");
  // Hand-placed from the mesh (y up, nose at +z): torso, head, tail, two bones per leg.
  std::vector<std::pair<Vec3, Vec3>> bones = {{{0, 0.6, -0.4}, {0, 0.62, 0.4}},
                                              {{0, 0.62, 0.4}, {0, 0.78, 0.8}},
                                              {{0, 0.62, -0.4}, {0, 0.66, -1.12}}};
  std::vector<std::int32_t> parents = {-1, 0, 0};
  for (double side : {-1.0, 1.0}) {
    const std::int32_t front = static_cast<std::int32_t>(bones.size());
    bones.push_back({{side * 0.1, 0.45, 0.36}, {side * 0.11, 0.25, 0.39}});
    bones.push_back({{side * 0.11, 0.25, 0.39}, {side * 0.11, 0.03, 0.45}});
    bones.push_back({{side * 0.11, 0.45, -0.22}, {side * 0.12, 0.22, -0.28}});
    bones.push_back({{side * 0.12, 0.22, -0.28}, {side * 0.12, 0.03, -0.23}});
    parents.insert(parents.end(), {0, front, 0, front + 2});
  }
  d.skeleton = skeletonOf(bones, parents);
  d.influences = nearestBoneWeights(d.mesh.positions, d.skeleton);
  return d;
}

TEST(IsoCurvesData, CatIsFastAndFullyBound) {
  const Dataset d = cat();
  ASSERT_EQ(d.mesh.positions.size(), 7207u);
  const auto start = std::chrono::steady_clock::now();
  Result<CurveSet> set = buildIsoCurves(d.mesh.positions, d.mesh.faces, d.skeleton, d.influences);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_TRUE(set.ok()) << set.status().toString();
  const Summary s = expectWellFormed(*set, d.mesh.positions.size());
  std::printf("cat-00: %zu curves (%zu closed) over %zu parts, %zu of %zu vertices between two curves, %.3f s\n",
              s.curves, s.closed, s.parts.size(), s.paired, d.mesh.positions.size(), seconds);
  EXPECT_EQ(s.parts.size(), d.skeleton.boneCount());
  // Tube-like parts (tail, lower legs) get rings; the torso's open arcs come from the crude
  // nearest-bone rig, whose leg patches reach up under it.
  std::size_t tube_curves = 0, tube_closed = 0;
  for (const IsoCurve& c : set->curves) {
    if (c.part == 2 || c.part == 4 || c.part == 6 || c.part == 8 || c.part == 10) {
      ++tube_curves;
      tube_closed += c.closed ? 1 : 0;
    }
  }
  std::printf("cat-00: tail and lower legs %zu of %zu curves closed\n", tube_closed, tube_curves);
  EXPECT_GE(tube_curves, 15u);
  EXPECT_GT(static_cast<double>(tube_closed), 0.9 * static_cast<double>(tube_curves));
  EXPECT_GT(static_cast<double>(s.closed), 0.5 * static_cast<double>(s.curves));
  EXPECT_LT(seconds, 2.0);  // typically well under a second in Release

  // A smooth field (wavelength ~ the cat's length) through the curves and bindings: most
  // vertices are represented closely; the tail of the distribution is ears, the face beyond the
  // last head curve and parts cut into arcs by the crude rig.
  Vec3 lo(1e9), hi(-1e9);
  for (const Vec3& p : d.mesh.positions) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  const double diagonal = glm::length(hi - lo);
  const FieldError e = bindingError(*set, d.mesh.positions, [&](const Vec3& p) {
    const Vec3 q = 6.0 * (p - lo) / diagonal;
    return Vec3(std::sin(q.y + 0.5 * q.z), std::cos(q.z - q.x), std::sin(q.x + q.y));
  });
  std::printf("cat-00 smooth field: median %.4f, 90%% %.4f, max %.4f of max |u| %.3f\n", e.quantile(0.5),
              e.quantile(0.9), e.max, e.scale);
  EXPECT_LT(e.quantile(0.5), 0.025 * e.scale);
  EXPECT_LT(e.quantile(0.9), 0.12 * e.scale);
}

TEST(IsoCurvesData, HorseWithHoles) {
  Dataset d;
  d.mesh = loadObj(kData + "/horse-gallop/horse-01.obj");
  ASSERT_EQ(d.mesh.positions.size(), 8431u);
  std::vector<std::pair<Vec3, Vec3>> bones = {{{0, 0.85, -0.6}, {0, 0.9, 0.2}},
                                              {{0, 0.9, 0.2}, {0, 1.25, 0.5}},
                                              {{0, 1.25, 0.5}, {0, 0.98, 0.68}},
                                              {{0, 1.0, -0.6}, {0, 1.12, -1.3}}};
  std::vector<std::int32_t> parents = {-1, 0, 1, 0};
  // Legs of frame 1 (hips and shoulders, knees, hooves), hand-placed.
  const std::vector<std::array<Vec3, 3>> legs = {{{{-0.12, 0.62, -0.6}, {-0.11, 0.46, -0.77}, {-0.11, 0.15, -0.99}}},
                                                 {{{0.13, 0.62, -0.52}, {0.12, 0.45, -0.62}, {0.10, 0.05, -0.73}}},
                                                 {{{-0.12, 0.62, 0.2}, {-0.12, 0.45, 0.11}, {-0.11, 0.05, 0.03}}},
                                                 {{{0.12, 0.62, 0.3}, {0.12, 0.45, 0.45}, {0.11, 0.14, 0.71}}}};
  for (const auto& leg : legs) {
    const std::int32_t upper = static_cast<std::int32_t>(bones.size());
    bones.push_back({leg[0], leg[1]});
    bones.push_back({leg[1], leg[2]});
    parents.insert(parents.end(), {0, upper});
  }
  d.skeleton = skeletonOf(bones, parents);
  d.influences = nearestBoneWeights(d.mesh.positions, d.skeleton);
  Result<CurveSet> set = buildIsoCurves(d.mesh.positions, d.mesh.faces, d.skeleton, d.influences);
  ASSERT_TRUE(set.ok()) << set.status().toString();
  const Summary s = expectWellFormed(*set, d.mesh.positions.size());
  std::printf("horse-01: %zu curves (%zu closed, %zu open) over %zu parts, %zu of %zu vertices between two curves\n",
              s.curves, s.closed, s.curves - s.closed, s.parts.size(), s.paired, d.mesh.positions.size());
  EXPECT_EQ(s.parts.size(), d.skeleton.boneCount());
  // The 16-edge hole at a front hoof: cuts through it stay open and end on its rim; no closed
  // curve runs along a rim edge (the 3-edge hole on the head is too small to matter).
  Result<PolyMesh> poly = buildPolyMesh(d.mesh.positions, d.mesh.faces, "horse-01");
  ASSERT_TRUE(poly.ok());
  const auto loops = boundaryLoops(*poly);
  ASSERT_EQ(loops.size(), 2u);
  std::set<std::uint32_t> rim_vertices;
  std::set<std::pair<std::uint32_t, std::uint32_t>> rim_edges;
  for (const auto& loop : loops) {
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const auto a = loop[k], b = loop[(k + 1) % loop.size()];
      rim_vertices.insert(a);
      rim_edges.insert({std::min(a, b), std::max(a, b)});
    }
  }
  auto onRim = [&](const CurvePoint& p) {
    return p.a == p.b ? rim_vertices.count(p.a) > 0 : rim_edges.count({std::min(p.a, p.b), std::max(p.a, p.b)}) > 0;
  };
  std::size_t open_on_rim = 0;
  for (const IsoCurve& c : set->curves) {
    for (const CurvePoint& p : c.points) {
      if (p.a != p.b && rim_edges.count({std::min(p.a, p.b), std::max(p.a, p.b)})) {
        EXPECT_FALSE(c.closed) << "a closed curve crosses the rim of a hole";
      }
    }
    if (!c.closed && (onRim(c.points.front()) || onRim(c.points.back()))) ++open_on_rim;
  }
  std::printf("horse-01: %zu open curves end on a hole's rim\n", open_on_rim);
  EXPECT_GE(open_on_rim, 1u);
}

TEST(IsoCurvesData, CheburashkaWithItsRig) {
  Dataset d;
  d.mesh = loadObj(kData + "/cheburashka/cheburashka.obj");
  d.skeleton = readTgf(kData + "/cheburashka/cheburashka.tgf");
  d.influences = readDmatWeights(kData + "/cheburashka/cheburashka.DMAT");
  ASSERT_EQ(d.skeleton.boneCount(), 11u);
  ASSERT_EQ(d.influences.vertexCount(), d.mesh.positions.size());
  Result<CurveSet> set = buildIsoCurves(d.mesh.positions, d.mesh.faces, d.skeleton, d.influences);
  ASSERT_TRUE(set.ok()) << set.status().toString();
  const Summary s = expectWellFormed(*set, d.mesh.positions.size());
  std::printf("cheburashka: %zu curves (%zu closed) over %zu parts, %zu of %zu vertices between two curves\n",
              s.curves, s.closed, s.parts.size(), s.paired, d.mesh.positions.size());
  EXPECT_GE(s.parts.size(), 9u);
}

}  // namespace
}  // namespace odeskin
