// SPDX-License-Identifier: MIT
#include "engine/core/position_box.hpp"

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace odeskin {
namespace {

// The status is kInvalidArgument with exactly `message`.
void expectRefused(const Result<PositionBox>& box, const std::string& message) {
  ASSERT_FALSE(box.ok()) << message;
  EXPECT_EQ(box.status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(box.status().message(), message);
}

TEST(CheckedPositionBox, BoxAndDiagonal) {
  const std::vector<Vec3> points{{1.0, -2.0, 0.5}, {4.0, 2.0, 0.5}, {2.0, 0.0, -11.5}};
  const Result<PositionBox> box = checkedPositionBox(points, "test");
  ASSERT_TRUE(box.ok()) << box.status().toString();
  EXPECT_EQ(box->lo, Vec3(1.0, -2.0, -11.5));
  EXPECT_EQ(box->hi, Vec3(4.0, 2.0, 0.5));
  EXPECT_DOUBLE_EQ(box->diagonal, 13.0);  // |(3, 4, 12)|
  const Result<PositionBox> none = checkedPositionBox({}, "test");
  ASSERT_TRUE(none.ok());
  EXPECT_EQ(none->diagonal, 0.0);
}

TEST(CheckedPositionBox, NamesTheFirstVertexThatIsNotFinite) {
  std::vector<Vec3> points(6, Vec3(1.0));
  points[4].y = std::numeric_limits<double>::quiet_NaN();
  points[5].z = std::numeric_limits<double>::infinity();
  expectRefused(checkedPositionBox(points, "fit: pose 2"), "fit: pose 2: vertex 4 is not finite");
  expectRefused(checkedPositionBox(points, "the pose", 1), "the pose: vertex 5 is not finite");
  expectRefused(checkedPositionBox(points, "", 1), "vertex 5 is not finite");
}

TEST(CheckedPositionBox, RefusesMeshesTooLargeForLengths) {
  // Finite coordinates whose squared differences overflow.
  const std::vector<Vec3> huge{{0.0, 0.0, 0.0}, {2e200, 0.0, 0.0}};
  expectRefused(checkedPositionBox(huge, "rig"),
                "rig: the mesh is too large for double-precision distances (its bounding box spans 2e+200); scale it down");
  expectRefused(checkedPositionBox(huge, ""),
                "the mesh is too large for double-precision distances (its bounding box spans 2e+200); scale it down");
  // The squared diagonal decides: 1e150 across is measured, 1e160 is not.
  EXPECT_TRUE(checkedPositionBox(std::vector<Vec3>{Vec3(0.0), Vec3(1e150)}, "rig").ok());
  EXPECT_FALSE(checkedPositionBox(std::vector<Vec3>{Vec3(0.0), Vec3(1e160)}, "rig").ok());
}

TEST(CheckedPositionBox, RefusesMeshesTooFarFromTheOriginForSums) {
  // 1 across, but its centroid's sum overflows.
  const std::vector<Vec3> far{{1e308, 0.0, 0.0}, {1e308, 1.0, 0.0}, {1e308, 0.0, 1.0}};
  expectRefused(checkedPositionBox(far, "rig"),
                "rig: the mesh lies too far from the origin for double-precision sums (coordinates up to 1e+308); move it "
                "towards the origin");
  // The vertex count decides, on either side of the origin: V x |coordinate| must stay finite.
  const std::vector<Vec3> ten(10, Vec3(-1e306, 0.0, 0.0));
  EXPECT_TRUE(checkedPositionBox(ten, "rig").ok());
  const std::vector<Vec3> thousand(1000, Vec3(-1e306, 0.0, 0.0));
  EXPECT_FALSE(checkedPositionBox(thousand, "rig").ok());
}

TEST(CheckedPositionBox, RefusesMeshesTooSmallForLengths) {
  expectRefused(checkedPositionBox(std::vector<Vec3>{Vec3(0.0), Vec3(5e-120, 0.0, 0.0)}, "rig"),
                "rig: the mesh is too small for double-precision distances (its bounding box spans 5e-120); scale it up");
  // So small that the diagonal's square is 0.
  EXPECT_FALSE(checkedPositionBox(std::vector<Vec3>{Vec3(0.0), Vec3(3e-200, 4e-200, 0.0)}, "rig").ok());
  EXPECT_TRUE(checkedPositionBox(std::vector<Vec3>{Vec3(0.0), Vec3(1e-100, 0.0, 0.0)}, "rig").ok());
  // All at one point is not too small: the callers say what they need instead.
  const Result<PositionBox> point = checkedPositionBox(std::vector<Vec3>(3, Vec3(1e-200)), "rig");
  ASSERT_TRUE(point.ok());
  EXPECT_EQ(point->diagonal, 0.0);
}

}  // namespace
}  // namespace odeskin
