// SPDX-License-Identifier: MIT
#include "engine/baselines/pose_space_deformation.hpp"

#include <numeric>
#include <vector>

#include <gtest/gtest.h>

#include "arm_fixture.hpp"
#include "engine/baselines/skinning_baseline.hpp"

namespace odeskin {
namespace {

using testing::armBones;
using testing::armPose;
using testing::makeArmKeys;
using testing::maxDistance;

constexpr double kBulge = 0.4;

PoseSpaceDeformation makePsd(const testing::ArmKeys& arm, SkinningMode mode, const PsdOptions& options = {}) {
  Result<BaselineRig> rig = BaselineRig::fromAsset(arm.asset);
  EXPECT_TRUE(rig.ok());
  Result<PoseSpaceDeformation> psd = PoseSpaceDeformation::create(std::move(*rig), arm.keys, mode, options);
  EXPECT_TRUE(psd.ok()) << psd.status().toString();
  return std::move(*psd);
}

TEST(PoseSpaceDeformation, ReproducesEveryKeyWithItsSkeleton) {
  const testing::ArmKeys arm = makeArmKeys({0.0, 50.0, 110.0}, kBulge);
  for (SkinningMode mode : {SkinningMode::kLinear, SkinningMode::kDualQuaternion}) {
    PoseSpaceDeformation psd = makePsd(arm, mode);
    EXPECT_EQ(psd.name(), mode == SkinningMode::kLinear ? "psd_lbs" : "psd_dqs");
    std::vector<Vec3> out(psd.vertexCount());
    for (std::uint32_t k = 0; k < 3; ++k) {
      // Keys protocol (the key transforms) and truth protocol (the same bones given explicitly).
      const std::uint32_t segment = k == 2 ? 1 : k;
      const double tau = k == 2 ? 1.0 : 0.0;
      ASSERT_TRUE(psd.evaluate({segment, tau, {}}, out).ok());
      EXPECT_LT(maxDistance(out, arm.keys[k]), 1e-9) << psd.name() << " key " << k;
      const std::vector<BoneTransform> bones = armBones(arm.bends[k]);
      ASSERT_TRUE(psd.evaluate({0, 0.5, bones}, out).ok());
      EXPECT_LT(maxDistance(out, arm.keys[k]), 1e-9) << psd.name() << " key " << k << " (given bones)";
    }
  }
}

TEST(PoseSpaceDeformation, WeightsAreCardinalAtKeysAndSumToOne) {
  const testing::ArmKeys arm = makeArmKeys({0.0, 50.0, 110.0}, kBulge);
  PoseSpaceDeformation psd = makePsd(arm, SkinningMode::kLinear);
  std::vector<double> a(3);
  for (std::size_t k = 0; k < 3; ++k) {
    psd.exampleWeights(armBones(arm.bends[k]), a);
    for (std::size_t l = 0; l < 3; ++l) EXPECT_NEAR(a[l], k == l ? 1.0 : 0.0, 1e-9);
  }
  for (double degrees : {20.0, 80.0, 130.0}) {
    psd.exampleWeights(armBones(degrees), a);
    EXPECT_NEAR(std::accumulate(a.begin(), a.end(), 0.0), 1.0, 1e-12) << degrees;
  }
}

TEST(PoseSpaceDeformation, RecoversACorrectiveLinearInTheJointAngle) {
  // The arm's corrective (the bulge) grows linearly with the bend, and the pose space here is the
  // elbow angle: the RBF's affine term reproduces it exactly, so PSD with the true skeleton
  // recovers unseen in-betweens, where plain LBS misses the whole bulge.
  const testing::ArmKeys arm = makeArmKeys({0.0, 50.0, 110.0}, kBulge);
  PoseSpaceDeformation psd = makePsd(arm, SkinningMode::kLinear);
  Result<BaselineRig> rig = BaselineRig::fromAsset(arm.asset);
  ASSERT_TRUE(rig.ok());
  SkinningBaseline lbs(std::move(*rig), SkinningMode::kLinear);
  std::vector<Vec3> out(psd.vertexCount()), plain(psd.vertexCount());
  for (double degrees : {25.0, 80.0}) {
    const std::vector<Vec3> truth = armPose(degrees, kBulge);
    const std::vector<BoneTransform> bones = armBones(degrees);
    ASSERT_TRUE(psd.evaluate({0, 0.5, bones}, out).ok());
    ASSERT_TRUE(lbs.evaluate({0, 0.5, bones}, plain).ok());
    const double psd_error = maxDistance(out, truth);
    const double lbs_error = maxDistance(plain, truth);
    EXPECT_LT(psd_error, 1e-9) << degrees;
    EXPECT_GT(lbs_error, 1e-3) << degrees;
  }
}

TEST(PoseSpaceDeformation, CorrectivesAreTheBindSpaceBulge) {
  // Key k is LBS(X + bulge_k), so r^k is bulge_k: the key's minus the rest pose with no bend.
  const testing::ArmKeys arm = makeArmKeys({0.0, 90.0}, kBulge);
  for (SkinningMode mode : {SkinningMode::kLinear, SkinningMode::kDualQuaternion}) {
    PoseSpaceDeformation psd = makePsd(arm, mode);
    const std::span<const Vec3> r0 = psd.corrective(0);
    for (const Vec3& r : r0) EXPECT_LT(glm::length(r), 1e-12);
    // The biceps lies on the upper arm (weight 1 on the fixed bone), where both skinnings are the
    // identity; its corrective is the bulge of the straight arm with the same amplitude.
    ArmOptions o = testing::armOptions(90.0, kBulge);
    o.bend_degrees = 0.0;
    Result<ProceduralArm> straight_arm = makeProceduralArm(o);
    ASSERT_TRUE(straight_arm.ok());
    const std::vector<Vec3>& straight = straight_arm->end_positions;
    const std::vector<Vec3> rest = arm.asset.rest_positions;
    double worst = 0.0;
    for (std::size_t i = 0; i < rest.size(); ++i) {
      if (rest[i].x > 0.35) continue;  // the upper arm, away from the elbow blend
      worst = std::max(worst, glm::length(psd.corrective(1)[i] - (straight[i] - rest[i])));
    }
    EXPECT_LT(worst, 1e-12);
  }
}

TEST(PoseSpaceDeformation, RejectsMismatchedKeys) {
  const testing::ArmKeys arm = makeArmKeys({0.0, 90.0}, kBulge);
  Result<BaselineRig> rig = BaselineRig::fromAsset(arm.asset);
  ASSERT_TRUE(rig.ok());
  std::vector<std::vector<Vec3>> three = arm.keys;
  three.push_back(arm.keys[1]);
  EXPECT_EQ(PoseSpaceDeformation::create(*rig, three, SkinningMode::kLinear).status().code(),
            StatusCode::kInvalidArgument);
  std::vector<std::vector<Vec3>> short_keys = arm.keys;
  short_keys[1].pop_back();
  EXPECT_EQ(PoseSpaceDeformation::create(*rig, short_keys, SkinningMode::kLinear).status().code(),
            StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace odeskin
