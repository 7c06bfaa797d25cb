// SPDX-License-Identifier: MIT
#include "engine/kernels/influences.hpp"

#include <gtest/gtest.h>

#include "engine/offline/rigid_transform.hpp"
#include "engine/test_meshes.hpp"

namespace odeskin {
namespace {

Influences threeVertices() {
  Influences in;
  in.offsets = {0, 1, 3, 8};
  in.bones = {0, 0, 1, 0, 1, 2, 3, 4};
  in.weights = {1.0, 0.25, 0.75, 0.4, 0.3, 0.15, 0.1, 0.05};
  return in;
}

TEST(Influences, ValidLayoutPasses) {
  Influences in = threeVertices();
  EXPECT_TRUE(validateInfluences(in, 3, 5).ok());
  EXPECT_EQ(in.maxInfluences(), 5u);
}

TEST(Influences, EachDefectHasItsError) {
  auto expectInvalid = [](const Influences& in, std::size_t v, std::uint32_t b, const char* what) {
    Status s = validateInfluences(in, v, b);
    EXPECT_EQ(s.code(), StatusCode::kInvalidArgument) << what;
    EXPECT_FALSE(s.message().empty());
  };
  expectInvalid(threeVertices(), 4, 5, "vertex count");
  expectInvalid(threeVertices(), 3, 4, "bone index out of range");
  { Influences in = threeVertices(); in.weights[1] = -0.25; in.weights[2] = 1.25; expectInvalid(in, 3, 5, "negative weight"); }
  { Influences in = threeVertices(); in.weights[0] = 0.9; expectInvalid(in, 3, 5, "sum"); }
  { Influences in = threeVertices(); in.offsets = {0, 1, 1, 8}; in.bones.erase(in.bones.begin() + 1, in.bones.begin() + 3);
    in.weights.erase(in.weights.begin() + 1, in.weights.begin() + 3); in.offsets = {0, 1, 1, 6}; expectInvalid(in, 3, 5, "unbound vertex"); }
  { Influences in = threeVertices(); in.weights[0] = std::nan(""); expectInvalid(in, 3, 5, "NaN"); }
  { Influences in = threeVertices(); in.offsets[1] = 100; expectInvalid(in, 3, 5, "a middle offset past the arrays"); }
}

TEST(Influences, FromDenseDropsZeros) {
  const std::vector<double> dense{1.0, 0.0, 0.0, 0.5, 0.0, 0.5};
  Influences in = influencesFromDense(dense, 2, 3);
  EXPECT_EQ(in.offsets, (std::vector<std::uint32_t>{0, 1, 3}));
  EXPECT_EQ(in.bones, (std::vector<std::uint32_t>{0, 0, 2}));
}

TEST(Influences, FixedSlotsPadWithZeroWeights) {
  Result<FixedSlotInfluences> four = toFixedSlots(threeVertices(), 4);
  EXPECT_EQ(four.status().code(), StatusCode::kInvalidArgument);  // vertex 2 has 5
  Result<FixedSlotInfluences> eight = toFixedSlots(threeVertices(), 8);
  ASSERT_TRUE(eight.ok());
  EXPECT_EQ(eight->bones.size(), 24u);
  EXPECT_FLOAT_EQ(eight->weights[8 + 1], 0.75f);
  EXPECT_FLOAT_EQ(eight->weights[8 + 2], 0.0f);
  EXPECT_EQ(toFixedSlots(threeVertices(), 5).status().code(), StatusCode::kInvalidArgument);
}

TEST(Influences, PruneKeepsLargestRenormalisesAndReportsError) {
  const std::vector<Vec3> rest{Vec3(1.0, 0.0, 0.0), Vec3(0.0, 1.0, 0.0), Vec3(0.0, 0.0, 1.0)};
  std::vector<std::vector<BoneTransform>> poses{testing::randomBones(5, 3)};
  Result<PrunedInfluences> pruned = pruneInfluences(threeVertices(), 2, rest, poses);
  ASSERT_TRUE(pruned.ok());
  const Influences& p = pruned->influences;
  EXPECT_TRUE(validateInfluences(p, 3, 5).ok());
  EXPECT_EQ(p.offsets, (std::vector<std::uint32_t>{0, 1, 3, 5}));
  EXPECT_NEAR(p.weights[3], 0.4 / 0.7, 1e-15);
  EXPECT_EQ(pruned->report.vertices_pruned, 1u);
  EXPECT_NEAR(pruned->report.max_dropped_weight, 0.3, 1e-15);
  // Recompute the reported error independently for vertex 2.
  const auto skin = [&](const Influences& in) {
    Vec3 x(0.0);
    for (std::uint32_t k = in.offsets[2]; k < in.offsets[3]; ++k) {
      x += in.weights[k] * (poses[0][in.bones[k]] * glm::dvec4(rest[2], 1.0));
    }
    return x;
  };
  EXPECT_NEAR(pruned->report.max_position_error, glm::length(skin(p) - skin(threeVertices())), 1e-15);
  EXPECT_GT(pruned->report.max_position_error, 0.0);
  EXPECT_EQ(pruned->report.worst_vertex, 2u);
  EXPECT_EQ(pruneInfluences(threeVertices(), 0, rest, poses).status().code(), StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace odeskin
