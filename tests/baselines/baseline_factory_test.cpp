// SPDX-License-Identifier: MIT
#include "engine/baselines/baseline_factory.hpp"

#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "arm_fixture.hpp"

namespace odeskin {
namespace {

using testing::makeArmKeys;
using testing::maxDistance;

TEST(BaselineFactory, NamesRoundTrip) {
  for (std::uint32_t m = 0; m < kBaselineMethodCount; ++m) {
    BaselineMethod parsed{};
    ASSERT_TRUE(parseBaselineMethod(baselineMethodName(static_cast<BaselineMethod>(m)), &parsed));
    EXPECT_EQ(static_cast<std::uint32_t>(parsed), m);
  }
  BaselineMethod unused{};
  EXPECT_FALSE(parseBaselineMethod("lbs2", &unused));
  EXPECT_EQ(baselineMethodName(BaselineMethod::kOdeskinDynamic), "odeskin_dynamic");
}

TEST(BaselineFactory, EveryMethodReproducesTheKeysItShould) {
  // Keys that plain skinning cannot reach (a bulge): every method with a corrective (or no rig at
  // all) hits them within the asset's key tolerance; LBS and DQS miss them by the bulge.
  const testing::ArmKeys arm = makeArmKeys({0.0, 50.0, 110.0}, 0.4);
  const double box = longestBoxSide(arm.keys[1]);
  for (std::uint32_t m = 0; m < kBaselineMethodCount; ++m) {
    const auto method = static_cast<BaselineMethod>(m);
    Result<std::unique_ptr<Baseline>> built = makeBaseline(method, arm.keys, arm.asset);
    ASSERT_TRUE(built.ok()) << baselineMethodName(method) << ": " << built.status().toString();
    Baseline& b = **built;
    EXPECT_EQ(b.method(), method);
    std::vector<Vec3> out(b.vertexCount());
    double worst = 0.0;
    for (std::uint32_t k = 0; k < 3; ++k) {
      ASSERT_TRUE(b.evaluate({k == 2 ? 1u : k, k == 2 ? 1.0 : 0.0, {}}, out).ok());
      worst = std::max(worst, maxDistance(out, arm.keys[k]) / box);
    }
    std::printf("[ keys ] %-16s max key error %.2e of the box\n", std::string(b.name()).c_str(), worst);
    if (method == BaselineMethod::kLbs || method == BaselineMethod::kDqs) {
      EXPECT_GT(worst, 1e-3);
    } else {
      EXPECT_LT(worst, 1e-4);
    }
  }
}

TEST(BaselineFactory, RejectsKeysThatDoNotMatchTheAsset) {
  const testing::ArmKeys arm = makeArmKeys({0.0, 90.0}, 0.4);
  std::vector<std::vector<Vec3>> keys = arm.keys;
  keys.push_back(keys.back());
  EXPECT_EQ(makeBaseline(BaselineMethod::kLinear, keys, arm.asset).status().code(), StatusCode::kInvalidArgument);
  keys.pop_back();
  keys[0].pop_back();
  EXPECT_EQ(makeBaseline(BaselineMethod::kPsdLbs, keys, arm.asset).status().code(), StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace odeskin
