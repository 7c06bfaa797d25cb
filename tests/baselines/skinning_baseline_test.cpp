// SPDX-License-Identifier: MIT
#include "engine/baselines/skinning_baseline.hpp"

#include <vector>

#include <gtest/gtest.h>

#include "arm_fixture.hpp"

namespace odeskin {
namespace {

using testing::armBones;
using testing::armPose;
using testing::makeArmKeys;
using testing::maxDistance;

SkinningBaseline makeSkinning(const DeformAsset& asset, SkinningMode mode) {
  Result<BaselineRig> rig = BaselineRig::fromAsset(asset);
  EXPECT_TRUE(rig.ok()) << rig.status().toString();
  return SkinningBaseline(std::move(*rig), mode);
}

TEST(SkinningBaseline, ReproducesExactLbsPosesFromKeysAndFromGivenBones) {
  // Without a bulge every arm pose is plain LBS of the bind mesh.
  const testing::ArmKeys arm = makeArmKeys({0.0, 60.0, 120.0}, 0.0);
  SkinningBaseline lbs = makeSkinning(arm.asset, SkinningMode::kLinear);
  EXPECT_EQ(lbs.name(), "lbs");
  std::vector<Vec3> out(lbs.vertexCount());
  for (std::uint32_t k = 0; k < 3; ++k) {
    const std::uint32_t segment = k == 2 ? 1 : k;
    ASSERT_TRUE(lbs.evaluate({segment, k == 2 ? 1.0 : 0.0, {}}, out).ok());
    EXPECT_LT(maxDistance(out, arm.keys[k]), 1e-12) << "key " << k;
  }
  // Keys protocol between keys: the forearm's path is C1 through 60 degrees; at the middle of the
  // first segment squad gives 30 degrees about the same axis.
  ASSERT_TRUE(lbs.evaluate({0, 0.5, {}}, out).ok());
  EXPECT_LT(maxDistance(out, armPose(30.0, 0.0)), 1e-9);
  // Truth protocol: the caller's bones are used as given.
  const std::vector<BoneTransform> bones = armBones(75.0);
  ASSERT_TRUE(lbs.evaluate({1, 0.3, bones}, out).ok());
  EXPECT_LT(maxDistance(out, armPose(75.0, 0.0)), 1e-12);
}

// Mean distance of ring r's vertices from their centroid.
double ringRadius(std::span<const Vec3> positions, std::uint32_t ring, std::uint32_t per_ring) {
  Vec3 centre(0.0);
  for (std::uint32_t j = 0; j < per_ring; ++j) centre += positions[ring * per_ring + j] / static_cast<double>(per_ring);
  double sum = 0.0;
  for (std::uint32_t j = 0; j < per_ring; ++j) sum += glm::length(positions[ring * per_ring + j] - centre);
  return sum / per_ring;
}

TEST(SkinningBaseline, DualQuaternionsKeepTheElbowRingWhereLbsCollapsesIt) {
  // Two-bone bend by 120 degrees. The elbow ring has weights 1/2, 1/2: LBS blends the matrices,
  // (I + R)/2 scales the in-plane axis by cos 60 = 1/2; DQS turns the ring rigidly by 60 degrees.
  const testing::ArmKeys arm = makeArmKeys({0.0, 120.0}, 0.0);
  SkinningBaseline lbs = makeSkinning(arm.asset, SkinningMode::kLinear);
  SkinningBaseline dqs = makeSkinning(arm.asset, SkinningMode::kDualQuaternion);
  EXPECT_EQ(dqs.name(), "dqs");
  const std::vector<BoneTransform> bones = armBones(120.0);
  std::vector<Vec3> out_lbs(lbs.vertexCount()), out_dqs(dqs.vertexCount());
  ASSERT_TRUE(lbs.evaluate({0, 1.0, bones}, out_lbs).ok());
  ASSERT_TRUE(dqs.evaluate({0, 1.0, bones}, out_dqs).ok());
  const ArmOptions o = testing::armOptions(0.0, 0.0);
  const std::uint32_t elbow_ring = o.rings / 2;
  const double rest = ringRadius(arm.asset.rest_positions, elbow_ring, o.ring_vertices);
  const double r_lbs = ringRadius(out_lbs, elbow_ring, o.ring_vertices);
  const double r_dqs = ringRadius(out_dqs, elbow_ring, o.ring_vertices);
  EXPECT_NEAR(r_dqs, rest, 1e-12 * rest);
  // An ellipse with semi-axes rest and rest / 2 has mean radius ~0.77 rest.
  EXPECT_LT(r_lbs, 0.8 * rest);
  EXPECT_GT(r_lbs, 0.7 * rest);
  // Rigid vertices (far from the elbow) agree between the two.
  EXPECT_LT(glm::length(out_lbs[0] - out_dqs[0]), 1e-12);
  EXPECT_LT(glm::length(out_lbs.back() - out_dqs.back()), 1e-12);
}

TEST(SkinningBaseline, RejectsBadFrames) {
  const testing::ArmKeys arm = makeArmKeys({0.0, 90.0}, 0.0);
  SkinningBaseline lbs = makeSkinning(arm.asset, SkinningMode::kLinear);
  std::vector<Vec3> out(lbs.vertexCount());
  const std::vector<BoneTransform> one_bone(1);
  EXPECT_EQ(lbs.evaluate({0, 0.5, one_bone}, out).code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(lbs.evaluate({1, 0.5, {}}, out).code(), StatusCode::kOutOfRange);
  std::vector<Vec3> short_out(out.size() - 1);
  EXPECT_EQ(lbs.evaluate({0, 0.5, {}}, short_out).code(), StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace odeskin
