// SPDX-License-Identifier: MIT
#include "engine/rig/distance_weights.hpp"

#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "engine/io/obj_reader.hpp"
#include "engine/mesh/adjacency.hpp"

namespace odeskin {
namespace {

// The cylinder's skeleton from the data README: joints 1 (0,0,0), 2 (0.9,0,0), 3 (1.8,0,0),
// 4 (-0.9,0,0), 5 (-1.8,0,0); bones 1->2, 2->3, 1->4, 4->5 with parents [-1, 0, -1, 2].
Skeleton cylinderSkeleton() {
  Skeleton s;
  s.parents = {-1, 0, -1, 2};
  s.heads = {Vec3(0.0), Vec3(0.9, 0.0, 0.0), Vec3(0.0), Vec3(-0.9, 0.0, 0.0)};
  s.tails = {Vec3(0.9, 0.0, 0.0), Vec3(1.8, 0.0, 0.0), Vec3(-0.9, 0.0, 0.0), Vec3(-1.8, 0.0, 0.0)};
  return s;
}

ObjMesh cylinder() {
  Result<ObjMesh> mesh = readObj(std::string(ODESKIN_DATA_DIR) + "/cylinder/cylinder.obj");
  if (!mesh.ok()) throw std::runtime_error(mesh.status().toString());
  return std::move(mesh).value();
}

double weightOf(const Influences& in, std::size_t vertex, std::uint32_t bone) {
  for (std::uint32_t e = in.offsets[vertex]; e < in.offsets[vertex + 1]; ++e) {
    if (in.bones[e] == bone) return in.weights[e];
  }
  return 0.0;
}

void expectPartitionOfUnity(const Influences& in, std::size_t vertices, std::uint32_t bones, std::uint32_t most) {
  ASSERT_TRUE(validateInfluences(in, vertices, bones, 1e-12).ok());
  EXPECT_LE(in.maxInfluences(), most);
  for (std::size_t i = 0; i < vertices; ++i) {
    double sum = 0.0;
    for (std::uint32_t e = in.offsets[i]; e < in.offsets[i + 1]; ++e) {
      EXPECT_GE(in.weights[e], 0.0);
      sum += in.weights[e];
    }
    EXPECT_NEAR(sum, 1.0, 1e-12) << "vertex " << i;
  }
}

TEST(DistanceWeights, CylinderWeightsAreNormalisedSmoothAndFollowTheBones) {
  const ObjMesh mesh = cylinder();
  const Skeleton skeleton = cylinderSkeleton();
  const Result<Influences> weights = distanceWeights(mesh.positions, mesh.faces, skeleton);
  ASSERT_TRUE(weights.ok()) << weights.status().toString();
  const std::size_t vertices = mesh.positions.size();
  expectPartitionOfUnity(*weights, vertices, 4, 4);

  // Smooth: across any mesh edge (0.2 along the tube, 0.16 around it) no weight jumps by more
  // than a sixth (measured: 0.115); the bones are 0.9 long, so a blend over a joint spans several
  // rings. The smoothing pass is what brings it there (measured without: 0.17).
  const VertexAdjacency adjacency = vertexAdjacency(mesh.faces, vertices);
  auto steepest = [&](const Influences& in) {
    double most = 0.0;
    for (std::uint32_t i = 0; i < vertices; ++i) {
      for (const std::uint32_t j : adjacency.of(i)) {
        for (std::uint32_t b = 0; b < 4; ++b) most = std::max(most, std::abs(weightOf(in, i, b) - weightOf(in, j, b)));
      }
    }
    return most;
  };
  EXPECT_LT(steepest(*weights), 1.0 / 6.0);
  DistanceWeightOptions unsmoothed;
  unsmoothed.smoothing_iterations = 0;
  const Result<Influences> raw = distanceWeights(mesh.positions, mesh.faces, skeleton, unsmoothed);
  ASSERT_TRUE(raw.ok()) << raw.status().toString();
  EXPECT_GT(steepest(*raw), steepest(*weights));

  for (std::uint32_t b = 0; b < 4; ++b) {
    const Vec3 middle = 0.5 * (skeleton.heads[b] + skeleton.tails[b]);
    std::size_t closest = 0;
    for (std::size_t i = 0; i < vertices; ++i) {
      if (glm::length(mesh.positions[i] - middle) < glm::length(mesh.positions[closest] - middle)) closest = i;
    }
    const double own = weightOf(*weights, closest, b);
    for (std::uint32_t other = 0; other < 4; ++other) {
      if (other != b) {
        EXPECT_GT(own, weightOf(*weights, closest, other)) << "bone " << b << " vs " << other;
      }
    }
    EXPECT_GT(own, 0.5) << "bone " << b;  // measured: 0.53 for the inner bones, 0.75 for the outer
  }
}

// Two parallel tubes (legs) along y, centred at x = -0.3 and x = +0.3, radius 0.2: separate
// components of one mesh, 0.2 apart.
ObjMesh twoLegs() {
  ObjMesh mesh;
  constexpr int kRings = 11;
  constexpr int kAround = 12;
  for (const double cx : {-0.3, 0.3}) {
    const auto base = static_cast<std::uint32_t>(mesh.positions.size());
    for (int r = 0; r < kRings; ++r) {
      for (int a = 0; a < kAround; ++a) {
        const double angle = 2.0 * std::numbers::pi * a / kAround;
        mesh.positions.push_back(Vec3(cx + 0.2 * std::cos(angle), 0.1 * r, 0.2 * std::sin(angle)));
      }
    }
    for (int r = 0; r + 1 < kRings; ++r) {
      for (int a = 0; a < kAround; ++a) {
        const auto v = [&](int rr, int aa) { return base + static_cast<std::uint32_t>(rr * kAround + (aa % kAround)); };
        for (const std::uint32_t index : {v(r, a), v(r, a + 1), v(r + 1, a + 1), v(r + 1, a)}) {
          mesh.faces.indices.push_back(index);
        }
        mesh.faces.face_offsets.push_back(static_cast<std::uint32_t>(mesh.faces.indices.size()));
      }
    }
  }
  return mesh;
}

TEST(DistanceWeights, OneLegTakesNoWeightFromTheOther) {
  const ObjMesh mesh = twoLegs();
  // A pelvis bone across the top at y = 1.5, the legs hanging from its ends: every vertex is
  // nearest its own leg's bone.
  Skeleton s;
  s.parents = {-1, 0, 0};
  s.heads = {Vec3(-0.3, 1.5, 0.0), Vec3(-0.3, 1.5, 0.0), Vec3(0.3, 1.5, 0.0)};
  s.tails = {Vec3(0.3, 1.5, 0.0), Vec3(-0.3, 0.0, 0.0), Vec3(0.3, 0.0, 0.0)};
  const Result<Influences> weights = distanceWeights(mesh.positions, mesh.faces, s);
  ASSERT_TRUE(weights.ok()) << weights.status().toString();
  expectPartitionOfUnity(*weights, mesh.positions.size(), 3, 4);
  // Plain inverse distance would give an inner-thigh vertex (0.2 from its bone, 0.4 from the other)
  // 1/17 of its weight from the other leg.
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    const bool left = mesh.positions[i].x < 0.0;
    EXPECT_EQ(weightOf(*weights, i, left ? 2 : 1), 0.0) << "vertex " << i;
    EXPECT_GT(weightOf(*weights, i, left ? 1 : 2), 0.9) << "vertex " << i;
  }
}

TEST(DistanceWeights, PruningAndOptions) {
  const ObjMesh mesh = cylinder();
  const Skeleton skeleton = cylinderSkeleton();
  DistanceWeightOptions options;
  options.max_influences = 2;
  Result<Influences> weights = distanceWeights(mesh.positions, mesh.faces, skeleton, options);
  ASSERT_TRUE(weights.ok()) << weights.status().toString();
  expectPartitionOfUnity(*weights, mesh.positions.size(), 4, 2);
  // A sharper falloff concentrates the weights: the least dominated vertex gains.
  auto weakestDominance = [&](const Influences& in) {
    double weakest = 1.0;
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
      double top = 0.0;
      for (std::uint32_t e = in.offsets[i]; e < in.offsets[i + 1]; ++e) top = std::max(top, in.weights[e]);
      weakest = std::min(weakest, top);
    }
    return weakest;
  };
  options = {};
  options.smoothing_iterations = 0;
  const Result<Influences> soft = distanceWeights(mesh.positions, mesh.faces, skeleton, options);
  options.falloff_power = 12.0;
  const Result<Influences> sharp = distanceWeights(mesh.positions, mesh.faces, skeleton, options);
  ASSERT_TRUE(soft.ok() && sharp.ok());
  EXPECT_GT(weakestDominance(*sharp), weakestDominance(*soft));
}

TEST(DistanceWeights, BadInput) {
  const ObjMesh mesh = cylinder();
  const Skeleton skeleton = cylinderSkeleton();
  EXPECT_EQ(distanceWeights(mesh.positions, mesh.faces, Skeleton{}).status().code(), StatusCode::kInvalidArgument);
  Skeleton cycle = skeleton;
  cycle.parents[0] = 1;
  EXPECT_EQ(distanceWeights(mesh.positions, mesh.faces, cycle).status().code(), StatusCode::kInvalidArgument);
  FaceList bad = mesh.faces;
  bad.indices[5] = 420;
  EXPECT_EQ(distanceWeights(mesh.positions, bad, skeleton).status().code(), StatusCode::kInvalidArgument);
  bad = mesh.faces;
  bad.face_offsets.back() += 1;
  EXPECT_EQ(distanceWeights(mesh.positions, bad, skeleton).status().code(), StatusCode::kInvalidArgument);
  std::vector<Vec3> positions = mesh.positions;
  positions[3].z = std::numeric_limits<double>::infinity();
  EXPECT_EQ(distanceWeights(positions, mesh.faces, skeleton).status().code(), StatusCode::kInvalidArgument);
  // Finite, but its squared distances overflow: refused, not weights from infinite distances.
  positions = mesh.positions;
  for (Vec3& p : positions) p *= 1e200;
  Skeleton huge = skeleton;
  for (Vec3& p : huge.heads) p *= 1e200;
  for (Vec3& p : huge.tails) p *= 1e200;
  const Status too_large = distanceWeights(positions, mesh.faces, huge).status();
  EXPECT_EQ(too_large.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(too_large.message().find("distance weights: the mesh is too large"), std::string::npos) << too_large.message();
  for (const auto& change : {+[](DistanceWeightOptions& o) { o.max_influences = 0; },
                             +[](DistanceWeightOptions& o) { o.falloff_power = 0.0; },
                             +[](DistanceWeightOptions& o) { o.falloff_power = std::numeric_limits<double>::quiet_NaN(); },
                             +[](DistanceWeightOptions& o) { o.smoothing_iterations = -1; }}) {
    DistanceWeightOptions options;
    change(options);
    EXPECT_EQ(distanceWeights(mesh.positions, mesh.faces, skeleton, options).status().code(),
              StatusCode::kInvalidArgument);
  }
}

}  // namespace
}  // namespace odeskin
