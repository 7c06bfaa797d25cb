// SPDX-License-Identifier: MIT
#include "engine/baselines/odeskin_baseline.hpp"

#include <vector>

#include <gtest/gtest.h>

#include "arm_fixture.hpp"
#include "engine/offline/deform_player.hpp"

namespace odeskin {
namespace {

using testing::armBones;
using testing::armPose;
using testing::makeArmKeys;
using testing::maxDistance;

constexpr double kBulge = 0.4;

std::vector<Vec3> evaluate(Baseline& method, std::uint32_t segment, double tau, std::span<const BoneTransform> bones = {}) {
  std::vector<Vec3> out(method.vertexCount());
  const Status s = method.evaluate({segment, tau, bones}, out);
  EXPECT_TRUE(s.ok()) << s.toString();
  return out;
}

TEST(OdeskinBaseline, KeepingTheAssetsMaterialIsThePlayerItself) {
  const testing::ArmKeys arm = makeArmKeys({0.0, 50.0, 110.0}, kBulge, 5, skinMaterial());
  Result<OdeskinBaseline> adapter = OdeskinBaseline::create(arm.asset, std::nullopt, BaselineMethod::kOdeskinDynamic);
  ASSERT_TRUE(adapter.ok()) << adapter.status().toString();
  EXPECT_EQ(adapter->name(), "odeskin_dynamic");
  Result<DeformPlayer> player = DeformPlayer::create(arm.asset);
  ASSERT_TRUE(player.ok());
  std::vector<ModeBasisValue> basis(player->basisSize());
  std::vector<BoneTransform> bones(arm.asset.bone_count);
  std::vector<Vec3> direct(arm.asset.vertexCount());
  for (const auto& [segment, tau] : {std::pair<std::uint32_t, double>{0, 0.3}, {1, 0.0}, {1, 0.8}}) {
    player->basisAt(tau, basis);
    player->bonesAt(arm.asset, segment, tau, bones);
    ASSERT_TRUE(referenceJob(arm.asset, segment, basis, bones, direct).run().ok());
    EXPECT_EQ(evaluate(*adapter, segment, tau), direct) << segment << " " << tau;
  }
}

TEST(OdeskinBaseline, StaticBlendsTheBindSpaceCorrectiveLinearly) {
  // Two keys, bulge linear in the angle: at tau = 1/2 the bones are at the mid angle and the static
  // deformer adds half the corrective, which is the exact arm there (up to the key tolerance).
  const testing::ArmKeys arm = makeArmKeys({0.0, 90.0}, kBulge);
  Result<OdeskinBaseline> fixed = OdeskinBaseline::create(arm.asset, staticMaterial(), BaselineMethod::kOdeskinStatic);
  ASSERT_TRUE(fixed.ok());
  EXPECT_EQ(fixed->name(), "odeskin_static");
  const double box = longestBoxSide(arm.keys[1]);
  const std::vector<Vec3> truth = armPose(45.0, kBulge);
  EXPECT_LT(maxDistance(evaluate(*fixed, 0, 0.5), truth), 1e-4 * box);
  // The truth protocol with those same bones gives the same frame.
  const std::vector<BoneTransform> bones = armBones(45.0);
  EXPECT_LT(maxDistance(evaluate(*fixed, 0, 0.5, bones), truth), 1e-4 * box);
}

TEST(OdeskinBaseline, DynamicDiffersFromStaticBetweenKeysOnly) {
  const testing::ArmKeys arm = makeArmKeys({0.0, 50.0, 110.0}, kBulge);
  Result<OdeskinBaseline> fixed = OdeskinBaseline::create(arm.asset, staticMaterial(), BaselineMethod::kOdeskinStatic);
  Result<OdeskinBaseline> dynamic = OdeskinBaseline::create(arm.asset, skinMaterial(), BaselineMethod::kOdeskinDynamic);
  ASSERT_TRUE(fixed.ok() && dynamic.ok());
  const double box = longestBoxSide(arm.keys[1]);
  for (std::uint32_t k = 0; k < 3; ++k) {
    const std::uint32_t segment = k == 2 ? 1 : k;
    const double tau = k == 2 ? 1.0 : 0.0;
    EXPECT_LT(maxDistance(evaluate(*fixed, segment, tau), arm.keys[k]), 1e-4 * box);
    EXPECT_LT(maxDistance(evaluate(*dynamic, segment, tau), arm.keys[k]), 1e-4 * box);
  }
  // Skin material starts as t^3 (MATH.md 5.3): at tau = 1/2 of the first segment it lags the
  // static blend by a visible fraction of the bulge.
  EXPECT_GT(maxDistance(evaluate(*fixed, 0, 0.5), evaluate(*dynamic, 0, 0.5)), 1e-3 * box);
}

TEST(OdeskinBaseline, RejectsOtherMethodsAndBadMaterials) {
  const testing::ArmKeys arm = makeArmKeys({0.0, 90.0}, kBulge);
  EXPECT_EQ(OdeskinBaseline::create(arm.asset, staticMaterial(), BaselineMethod::kLbs).status().code(),
            StatusCode::kInvalidArgument);
  EXPECT_EQ(OdeskinBaseline::create(arm.asset, Material{}, BaselineMethod::kOdeskinDynamic).status().code(),
            StatusCode::kDegenerate);
}

}  // namespace
}  // namespace odeskin
