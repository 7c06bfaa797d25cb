// SPDX-License-Identifier: MIT
#include "engine/kernels/lbs_job.hpp"

#include <cmath>
#include <limits>
#include <numbers>

#include <gtest/gtest.h>

#include "engine/kernels/fourier_deform_fast_job.hpp"
#include "engine/offline/deform_asset.hpp"
#include "engine/test_meshes.hpp"

namespace odeskin {
namespace {

TEST(LbsJob, SizesAndIndicesAreChecked) {
  std::vector<Vec3> rest(2, Vec3(1.0));
  Influences in;
  in.offsets = {0, 1, 2};
  in.bones = {0, 1};
  in.weights = {1.0, 1.0};
  std::vector<BoneTransform> bones(2, BoneTransform(1.0));
  std::vector<Vec3> out(2);
  EXPECT_TRUE((LbsJob{rest, in, bones, out}).validate().ok());
  EXPECT_EQ((LbsJob{rest, in, bones, std::span(out).first(1)}).validate().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ((LbsJob{rest, in, std::span(bones).first(1), out}).validate().code(), StatusCode::kInvalidArgument);
  in.weights[1] = 0.9;
  EXPECT_EQ((LbsJob{rest, in, bones, out}).validate().code(), StatusCode::kInvalidArgument);
}

// Dual quaternions took a NaN bone for the identity (nearestRotation's fallback): a finite, wrong
// vertex where LBS gave NaN. Both refuse it now.
TEST(LbsJob, NonFiniteBonesAreRefusedInBothModes) {
  std::vector<Vec3> rest{Vec3(0.3, -0.7, 1.1)};
  Influences in;
  in.offsets = {0, 2};
  in.bones = {0, 1};
  in.weights = {0.5, 0.5};
  for (const double bad : {std::nan(""), std::numeric_limits<double>::infinity()}) {
    for (const glm::length_t column : {0, 3}) {
      std::vector<BoneTransform> bones(2, BoneTransform(1.0));
      bones[1][column][column == 3 ? 2 : 0] = bad;
      std::vector<Vec3> out(1, Vec3(7.0));
      for (const SkinningMode mode : {SkinningMode::kLinear, SkinningMode::kDualQuaternion}) {
        const Status s = (LbsJob{rest, in, bones, out, mode}).run();
        EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
        EXPECT_EQ(s.message(), "lbs: bone 1 has a non-finite entry");
        EXPECT_EQ(out[0], Vec3(7.0));  // nothing written
      }
    }
  }
}

TEST(LbsJob, HandComputedBlend) {
  // Halfway between identity and a quarter turn about z: the classic LBS shrink (candy wrapper).
  std::vector<Vec3> rest{Vec3(1.0, 0.0, 0.0)};
  Influences in;
  in.offsets = {0, 2};
  in.bones = {0, 1};
  in.weights = {0.5, 0.5};
  const RigidTransform quarter = rotationAbout(Vec3(0.0), Vec3(0.0, 0.0, 1.0), std::numbers::pi / 2);
  std::vector<BoneTransform> bones{BoneTransform(1.0), quarter.matrix()};
  std::vector<Vec3> out(1);
  ASSERT_TRUE((LbsJob{rest, in, bones, out}).run().ok());
  EXPECT_NEAR(out[0].x, 0.5, 1e-15);
  EXPECT_NEAR(out[0].y, 0.5, 1e-15);
  EXPECT_NEAR(out[0].z, 0.0, 1e-15);
  const glm::dmat3 a = blendedLinearPart(in, bones, 0);
  EXPECT_NEAR(glm::determinant(a), 0.5, 1e-15);
}

TEST(LbsJob, DualQuaternionHandComputedBlend) {
  // The LBS case above with dual quaternions: the eighth turn, still at radius 1.
  std::vector<Vec3> rest{Vec3(1.0, 0.0, 0.0)};
  Influences in;
  in.offsets = {0, 2};
  in.bones = {0, 1};
  in.weights = {0.5, 0.5};
  const RigidTransform quarter = rotationAbout(Vec3(0.0), Vec3(0.0, 0.0, 1.0), std::numbers::pi / 2);
  std::vector<BoneTransform> bones{BoneTransform(1.0), quarter.matrix()};
  std::vector<Vec3> out(1);
  ASSERT_TRUE((LbsJob{rest, in, bones, out, SkinningMode::kDualQuaternion}).run().ok());
  EXPECT_NEAR(out[0].x, std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(out[0].y, std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(out[0].z, 0.0, 1e-15);
  EXPECT_EQ((LbsJob{rest, in, bones, out, static_cast<SkinningMode>(3)}).validate().code(),
            StatusCode::kInvalidArgument);
}

TEST(LbsJob, IdentityBonesGiveRestPose) {
  DeformAsset a = testing::randomAsset(500, 3, 2, 6, 4, 1, 2);
  std::vector<BoneTransform> bones(6, BoneTransform(1.0));
  std::vector<Vec3> out(500);
  ASSERT_TRUE((LbsJob{a.rest_positions, a.influences, bones, out}).run().ok());
  for (std::size_t i = 0; i < out.size(); ++i) ASSERT_LT(glm::length(out[i] - a.rest_positions[i]), 1e-14);
}

void expectLbsFastMatchesReference(SkinningMode skinning) {
  DeformAsset a = testing::randomAsset(3000, 3, 2, 10, 4, 1, 6);
  a.skinning = skinning;
  const std::vector<BoneTransform> bones = testing::randomBones(10, 7);
  std::vector<Vec3> expected(a.vertexCount());
  ASSERT_TRUE((LbsJob{a.rest_positions, a.influences, bones, expected, skinning}).run().ok());
  std::vector<gpu::BoneMatrix> gpu_bones(10);
  toGpuBones(bones, gpu_bones);
  for (std::uint32_t layout : {0u, 4u, 8u}) {
    Result<PackedDeformData> packed = packDeformAsset(a, layout);
    ASSERT_TRUE(packed.ok());
    std::vector<gpu::Float4> out(a.vertexCount());
    ASSERT_TRUE((LbsFastJob{&*packed, gpu_bones, out, 0}).run().ok());
    for (std::size_t i = 0; i < out.size(); ++i) {
      ASSERT_LT(glm::length(Vec3(out[i].x, out[i].y, out[i].z) - expected[i]), 1e-5) << "layout " << layout << " vertex " << i;
    }
  }
}

TEST(LbsFastJob, MatchesReferenceInEveryLayout) { expectLbsFastMatchesReference(SkinningMode::kLinear); }
TEST(LbsFastJob, DualQuaternionMatchesReferenceInEveryLayout) {
  expectLbsFastMatchesReference(SkinningMode::kDualQuaternion);
}

}  // namespace
}  // namespace odeskin
