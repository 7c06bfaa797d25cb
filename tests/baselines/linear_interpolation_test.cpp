// SPDX-License-Identifier: MIT
#include "engine/baselines/linear_interpolation.hpp"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

namespace odeskin {
namespace {

std::vector<std::vector<Vec3>> threeKeys() {
  return {{Vec3(0, 0, 0), Vec3(1, 0, 0)}, {Vec3(2, 0, 0), Vec3(1, 4, 0)}, {Vec3(2, 2, 0), Vec3(1, 4, 8)}};
}

TEST(LinearInterpolation, KeysAndMidpoints) {
  Result<LinearInterpolation> lin = LinearInterpolation::create(threeKeys());
  ASSERT_TRUE(lin.ok()) << lin.status().toString();
  EXPECT_EQ(lin->name(), "linear");
  std::vector<Vec3> out(2);
  ASSERT_TRUE(lin->evaluate({0, 0.0, {}}, out).ok());
  EXPECT_EQ(out[1], Vec3(1, 0, 0));
  ASSERT_TRUE(lin->evaluate({0, 0.5, {}}, out).ok());
  EXPECT_EQ(out[0], Vec3(1, 0, 0));
  EXPECT_EQ(out[1], Vec3(1, 2, 0));
  ASSERT_TRUE(lin->evaluate({1, 0.25, {}}, out).ok());
  EXPECT_EQ(out[0], Vec3(2, 0.5, 0));
  EXPECT_EQ(out[1], Vec3(1, 4, 2));
  // Key 1 from both sides, and the last key.
  std::vector<Vec3> before(2), after(2);
  ASSERT_TRUE(lin->evaluate({0, 1.0, {}}, before).ok());
  ASSERT_TRUE(lin->evaluate({1, 0.0, {}}, after).ok());
  EXPECT_EQ(before, threeKeys()[1]);
  EXPECT_EQ(after, threeKeys()[1]);
  ASSERT_TRUE(lin->evaluate({1, 1.0, {}}, out).ok());
  EXPECT_EQ(out, threeKeys()[2]);
}

TEST(LinearInterpolation, GlobalTimeLocatesSegments) {
  EXPECT_EQ(locateSegment(1.25, 2), (std::pair<std::uint32_t, double>(1, 0.25)));
  EXPECT_EQ(locateSegment(2.0, 2), (std::pair<std::uint32_t, double>(1, 1.0)));
  EXPECT_EQ(locateSegment(-3.0, 2), (std::pair<std::uint32_t, double>(0, 0.0)));
  EXPECT_EQ(locateSegment(7.0, 2), (std::pair<std::uint32_t, double>(1, 1.0)));
}

TEST(LinearInterpolation, RejectsBadInput) {
  EXPECT_EQ(LinearInterpolation::create({{Vec3(0.0)}}).status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(LinearInterpolation::create({{Vec3(0.0)}, {}}).status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(LinearInterpolation::create({{Vec3(0.0)}, {Vec3(std::nan(""))}}).status().code(),
            StatusCode::kInvalidArgument);
  Result<LinearInterpolation> lin = LinearInterpolation::create(threeKeys());
  ASSERT_TRUE(lin.ok());
  std::vector<Vec3> out(2), wrong(3);
  EXPECT_EQ(lin->evaluate({2, 0.0, {}}, out).code(), StatusCode::kOutOfRange);
  EXPECT_EQ(lin->evaluate({0, 0.5, {}}, wrong).code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(lin->evaluate({0, std::nan(""), {}}, out).code(), StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace odeskin
