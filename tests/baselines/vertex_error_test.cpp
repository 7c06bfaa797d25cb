// SPDX-License-Identifier: MIT
#include "engine/baselines/vertex_error.hpp"

#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

namespace odeskin {
namespace {

// Ground truth: a 2 x 1 x 0.5 box's corners (Lbox = 2, the longest edge, not the diagonal).
std::vector<Vec3> box() {
  return {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 1, 0), Vec3(2, 1, 0.5)};
}

TEST(VertexError, HandComputedValues) {
  const std::vector<Vec3> truth = box();
  std::vector<Vec3> deformed = truth;
  deformed[1] += Vec3(0.0, 0.3, 0.4);  // distance 0.5
  deformed[3] += Vec3(0.1, 0.0, 0.0);  // distance 0.1
  Result<VertexError> e = vertexError(deformed, truth);
  ASSERT_TRUE(e.ok()) << e.status().toString();
  EXPECT_DOUBLE_EQ(e->box_side, 2.0);
  EXPECT_DOUBLE_EQ(e->mve, 0.25);
  EXPECT_DOUBLE_EQ(e->mean, (0.5 + 0.1) / 4.0 / 2.0);
  EXPECT_EQ(e->worst_vertex, 1u);
}

TEST(VertexError, BoxComesFromTheGroundTruthOnly) {
  // A deformed mesh ten times larger must not change Lbox.
  const std::vector<Vec3> truth = box();
  std::vector<Vec3> deformed;
  deformed.reserve(truth.size());
  for (const Vec3& p : truth) deformed.push_back(10.0 * p);
  Result<VertexError> e = vertexError(deformed, truth);
  ASSERT_TRUE(e.ok());
  EXPECT_DOUBLE_EQ(e->box_side, 2.0);
  EXPECT_EQ(e->worst_vertex, 3u);
  EXPECT_DOUBLE_EQ(e->mve, 9.0 * glm::length(truth[3]) / 2.0);
}

TEST(VertexError, IdenticalMeshesHaveZeroError) {
  Result<VertexError> e = vertexError(box(), box());
  ASSERT_TRUE(e.ok());
  EXPECT_EQ(e->mve, 0.0);
  EXPECT_EQ(e->mean, 0.0);
}

TEST(VertexError, RejectsBadInput) {
  const std::vector<Vec3> truth = box();
  std::vector<Vec3> shorter(truth.begin(), truth.end() - 1);
  EXPECT_EQ(vertexError(shorter, truth).status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(vertexError({}, {}).status().code(), StatusCode::kInvalidArgument);
  std::vector<Vec3> bad = truth;
  bad[2].y = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(vertexError(bad, truth).status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(vertexError(truth, bad).status().code(), StatusCode::kInvalidArgument);
  const std::vector<Vec3> point(3, Vec3(1.0, 2.0, 3.0));
  EXPECT_EQ(vertexError(point, point).status().code(), StatusCode::kDegenerate);
}

}  // namespace
}  // namespace odeskin
