// SPDX-License-Identifier: MIT
// CPU/GPU parity of shaders/fourier_deform.comp and shaders/lbs.comp against FourierDeformFastJob
// and LbsFastJob on synthetic data: sizes 0, 1, 63, 65 (not multiples of the 64-wide workgroup)
// and 1000, every influence layout, both residual spaces, both skinning modes, N from 1 to 17.
// Tolerance 1e-5 absolute: both follow the same float order of operations; the gap is GPU cos/sin, sqrt and
// fused multiply-adds.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "engine/kernels/fourier_deform_fast_job.hpp"
#include "engine/random_packed_data.hpp"
#include "gpu_test_support.hpp"
#include "host/gpu_deformer.hpp"
#include "host/gpu_lbs.hpp"

namespace odeskin {
namespace {

using testing::GpuTest;
using testing::RandomPackedOptions;

constexpr float kTolerance = 1e-5f;

// Max |expected - actual| over every expectClose call since it was last reset.
float g_worst_parity = 0.0f;

// Max |expected - actual| over xyz, reported with the worst vertex.
void expectClose(const std::vector<gpu::Float4>& expected, const std::vector<gpu::Float4>& actual,
                 const std::string& what) {
  ASSERT_EQ(expected.size(), actual.size());
  float worst = 0.0f;
  std::size_t worst_index = 0;
  for (std::size_t i = 0; i < expected.size(); ++i) {
    const float diff = std::max({std::fabs(expected[i].x - actual[i].x), std::fabs(expected[i].y - actual[i].y),
                                 std::fabs(expected[i].z - actual[i].z), std::fabs(expected[i].w - actual[i].w)});
    if (!(diff <= worst)) {
      worst = diff;
      worst_index = i;
    }
  }
  if (expected.empty()) return;
  g_worst_parity = std::max(g_worst_parity, worst);
  const gpu::Float4& e = expected[worst_index];
  const gpu::Float4& a = actual[worst_index];
  EXPECT_LE(worst, kTolerance) << what << ": worst vertex " << worst_index << " expected (" << e.x << ", " << e.y
                               << ", " << e.z << ", " << e.w << ") actual (" << a.x << ", " << a.y << ", " << a.z
                               << ", " << a.w << ")";
}

std::string describe(const RandomPackedOptions& o) {
  return "V=" + std::to_string(o.vertex_count) + " N=" + std::to_string(o.modes) +
         " layout=" + std::to_string(o.influence_layout) +
         (o.residual_space == ResidualSpace::kBind ? " bind" : " posed") + (o.rates ? " rates" : " no-rates") +
         (o.skinning == SkinningMode::kDualQuaternion ? " dqs" : " lbs");
}

std::vector<RandomPackedOptions> parityCases(SkinningMode skinning = SkinningMode::kLinear) {
  std::vector<RandomPackedOptions> cases;
  std::uint32_t seed = 10;
  for (std::uint32_t v : {0u, 1u, 63u, 65u, 1000u}) {
    for (std::uint32_t layout : {0u, 4u, 8u}) {
      for (ResidualSpace space : {ResidualSpace::kBind, ResidualSpace::kPosed}) {
        // N odd and even, from 1 to 17: the fold and the series index the coefficients by N, so a
        // layout change that holds at one N can break at another.
        constexpr std::uint32_t kModes[] = {3, 1, 2, 4, 9, 6, 17};
        cases.push_back({v, layout, space, /*rates=*/(seed % 3) != 0, seed, skinning, kModes[seed % 7]});
        ++seed;
      }
    }
  }
  return cases;
}

void checkFourierDeformParity(const vk::Device& device, SkinningMode skinning) {
  for (const RandomPackedOptions& options : parityCases(skinning)) {
    const PackedDeformData data = testing::randomPackedData(options);
    Result<GpuDeformer> gpu = GpuDeformer::create(device, data);
    ASSERT_TRUE(gpu.ok()) << describe(options) << ": " << gpu.status().toString();
    for (std::uint32_t segment = 0; segment < data.segment_count; ++segment) {
      const auto bones = testing::randomGpuBones(data.bone_count, options.seed * 7 + segment);
      const auto basis = testing::randomGpuBasis(ODESKIN_BASIS_ENTRIES(std::size_t{data.material_count}, std::size_t{data.modes}),
                                              options.seed * 13 + segment);
      std::vector<gpu::Float4> expected(data.vertex_count);
      FourierDeformFastJob job;
      job.data = &data;
      job.segment = segment;
      job.bones = bones;
      job.basis = basis;
      job.out_positions = expected;
      ASSERT_TRUE(job.run().ok());

      GpuDeformFrame frame{segment, bones, basis};
      Status status = gpu->run(frame);
      ASSERT_TRUE(status.ok()) << describe(options) << ": " << status.toString();
      std::vector<gpu::Float4> actual(data.vertex_count);
      ASSERT_TRUE(gpu->readPositions(actual).ok());
      expectClose(expected, actual, describe(options) + " segment " + std::to_string(segment));
    }
  }
}

void checkLbsParity(const vk::Device& device, SkinningMode skinning) {
  for (const RandomPackedOptions& options : parityCases(skinning)) {
    const PackedDeformData data = testing::randomPackedData(options);
    Result<GpuLbs> gpu = GpuLbs::create(device, data);
    ASSERT_TRUE(gpu.ok()) << describe(options) << ": " << gpu.status().toString();
    const auto bones = testing::randomGpuBones(data.bone_count, options.seed);
    std::vector<gpu::Float4> expected(data.vertex_count);
    LbsFastJob job;
    job.data = &data;
    job.bones = bones;
    job.out_positions = expected;
    ASSERT_TRUE(job.run().ok());
    ASSERT_TRUE(gpu->run(GpuLbsFrame{bones}).ok());
    std::vector<gpu::Float4> actual(data.vertex_count);
    ASSERT_TRUE(gpu->readPositions(actual).ok());
    expectClose(expected, actual, "lbs " + describe(options));
  }
}

TEST_F(GpuTest, FourierDeformMatchesFastJob) { checkFourierDeformParity(device(), SkinningMode::kLinear); }
TEST_F(GpuTest, LbsMatchesFastJob) { checkLbsParity(device(), SkinningMode::kLinear); }

TEST_F(GpuTest, DualQuaternionFourierDeformMatchesFastJob) {
  g_worst_parity = 0.0f;
  checkFourierDeformParity(device(), SkinningMode::kDualQuaternion);
  std::printf("dual quaternion deform: max |fast - gpu| = %.3e\n", static_cast<double>(g_worst_parity));
}

TEST_F(GpuTest, DualQuaternionLbsMatchesFastJob) {
  g_worst_parity = 0.0f;
  checkLbsParity(device(), SkinningMode::kDualQuaternion);
  std::printf("dual quaternion skinning: max |fast - gpu| = %.3e\n", static_cast<double>(g_worst_parity));
}

// The two modes give different positions on these bones, so the parity above tests DQS itself.
TEST_F(GpuTest, SkinningModeChangesTheGpuOutput) {
  RandomPackedOptions options{1000, 0, ResidualSpace::kBind, true, 7};
  const auto bones = testing::randomGpuBones(7, 3);
  std::vector<gpu::Float4> lbs(options.vertex_count), dqs(options.vertex_count);
  for (SkinningMode mode : {SkinningMode::kLinear, SkinningMode::kDualQuaternion}) {
    options.skinning = mode;
    const PackedDeformData data = testing::randomPackedData(options);
    Result<GpuLbs> gpu = GpuLbs::create(device(), data);
    ASSERT_TRUE(gpu.ok()) << gpu.status().toString();
    ASSERT_TRUE(gpu->run(GpuLbsFrame{bones}).ok());
    ASSERT_TRUE(gpu->readPositions(mode == SkinningMode::kLinear ? lbs : dqs).ok());
  }
  float gap = 0.0f;
  for (std::size_t i = 0; i < lbs.size(); ++i) gap = std::max(gap, std::fabs(lbs[i].x - dqs[i].x));
  EXPECT_GT(gap, 1e-2f);
}

// Frames submitted back to back without waiting: each writes its own input slot, and the output
// after the wait is the last frame's.
TEST_F(GpuTest, DoubleBufferedFramesKeepTheirInputs) {
  const PackedDeformData data = testing::randomPackedData({1000, 0, ResidualSpace::kBind, true, 3});
  Result<GpuDeformer> gpu = GpuDeformer::create(device(), data);
  ASSERT_TRUE(gpu.ok());
  const auto basis = testing::randomGpuBasis(ODESKIN_BASIS_ENTRIES(std::size_t{data.material_count}, std::size_t{data.modes}), 5);
  std::vector<std::vector<gpu::BoneMatrix>> frames;
  for (std::uint32_t k = 0; k < 5; ++k) frames.push_back(testing::randomGpuBones(data.bone_count, 100 + k));
  for (const auto& bones : frames) ASSERT_TRUE(gpu->submit(GpuDeformFrame{1, bones, basis}).ok());
  ASSERT_TRUE(gpu->wait().ok());
  std::vector<gpu::Float4> expected(data.vertex_count);
  FourierDeformFastJob job;
  job.data = &data;
  job.segment = 1;
  job.bones = frames.back();
  job.basis = basis;
  job.out_positions = expected;
  ASSERT_TRUE(job.run().ok());
  std::vector<gpu::Float4> actual(data.vertex_count);
  ASSERT_TRUE(gpu->readPositions(actual).ok());
  expectClose(expected, actual, "last of 5 pipelined frames");
  EXPECT_GT(gpu->lastGpuSeconds(), 0.0);
  EXPECT_LT(gpu->lastGpuSeconds(), 10.0);
  const OutputBarrier barrier = gpu->outputBarrier();
  EXPECT_EQ(barrier.barrier.buffer, gpu->outputBuffer());
  EXPECT_EQ(barrier.barrier.dstAccessMask, static_cast<VkAccessFlags>(VK_ACCESS_VERTEX_ATTRIBUTE_READ_BIT));
}

// Same checks as FourierDeformFastJob::validate: every bad field gives kInvalidArgument.
TEST_F(GpuTest, DeformerValidatesLikeTheCpuJob) {
  const PackedDeformData data = testing::randomPackedData({65, 4, ResidualSpace::kPosed, false, 4});
  Result<GpuDeformer> gpu = GpuDeformer::create(device(), data);
  ASSERT_TRUE(gpu.ok());
  const auto bones = testing::randomGpuBones(data.bone_count, 1);
  const auto basis = testing::randomGpuBasis(ODESKIN_BASIS_ENTRIES(std::size_t{data.material_count}, std::size_t{data.modes}), 2);
  EXPECT_EQ(gpu->run({data.segment_count, bones, basis}).code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(gpu->run({0, std::span(bones).first(3), basis}).code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(gpu->run({0, bones, std::span(basis).first(1)}).code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(gpu->run({0, bones, {}}).code(), StatusCode::kInvalidArgument);
  std::vector<gpu::Float4> wrong(10);
  EXPECT_EQ(gpu->readPositions(wrong).code(), StatusCode::kInvalidArgument);

  PackedDeformData broken = data;
  broken.influences.pop_back();
  EXPECT_EQ(GpuDeformer::create(device(), broken).status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(GpuLbs::create(device(), broken).status().code(), StatusCode::kInvalidArgument);
  broken = data;
  broken.coefficients.pop_back();
  EXPECT_EQ(GpuDeformer::create(device(), broken).status().code(), StatusCode::kInvalidArgument);

  Result<GpuLbs> lbs = GpuLbs::create(device(), data);
  ASSERT_TRUE(lbs.ok());
  EXPECT_EQ(lbs->run({std::span(bones).first(6)}).code(), StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace odeskin
