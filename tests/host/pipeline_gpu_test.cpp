// SPDX-License-Identifier: MIT
// Assets fitted from real mesh sequences play the same on Vulkan as on the double-precision CPU
// reference (issue 3, point 7: "CPU and Vulkan agree as in the foundation issue"): within 1e-5 of
// the bounding box's longest side at keys and in-betweens, under the validation layer.
#include <gtest/gtest.h>

#include "../pipeline/dataset_fixtures.hpp"
#include "engine/offline/deform_player.hpp"
#include "engine/pipeline/fit_pipeline.hpp"
#include "gpu_test_support.hpp"
#include "host/gpu_deformer.hpp"

namespace odeskin {
namespace {

using testing::GpuTest;

void expectGpuMatchesReference(vk::Device& device, const DeformAsset& asset) {
  Result<PackedDeformData> packed = packDeformAsset(asset);
  ASSERT_TRUE(packed.ok()) << packed.status().toString();
  Result<GpuDeformer> gpu = GpuDeformer::create(device, *packed);
  ASSERT_TRUE(gpu.ok()) << gpu.status().toString();
  Result<DeformPlayer> player = DeformPlayer::create(asset);
  ASSERT_TRUE(player.ok());
  const double box = longestBoxSide(asset.rest_positions);
  std::vector<ModeBasisValue> basis(player->basisSize());
  std::vector<BoneTransform> bones(asset.bone_count);
  std::vector<gpu::ModeBasis> gpu_basis(basis.size());
  std::vector<gpu::BoneMatrix> gpu_bones(bones.size());
  std::vector<Vec3> expected(asset.vertexCount());
  std::vector<gpu::Float4> actual(asset.vertexCount());
  const double end = static_cast<double>(asset.segments.size());
  for (double t : {0.0, 0.37, 0.5, 1.0, end - 0.25, end}) {
    const auto [segment, tau] = player->locate(t);
    player->basisAt(tau, basis);
    player->bonesAt(asset, segment, tau, bones);
    ASSERT_TRUE(referenceJob(asset, segment, basis, bones, expected).run().ok());
    toGpuBasis(basis, gpu_basis);
    toGpuBones(bones, gpu_bones);
    ASSERT_TRUE(gpu->run(GpuDeformFrame{segment, gpu_bones, gpu_basis}).ok());
    ASSERT_TRUE(gpu->readPositions(actual).ok());
    double worst = 0.0;
    for (std::size_t i = 0; i < expected.size(); ++i) {
      const Vec3 got(actual[i].x, actual[i].y, actual[i].z);
      worst = std::max(worst, glm::length(got - expected[i]));
    }
    EXPECT_LT(worst / box, 1e-5) << "t = " << t;
  }
}

TEST_F(GpuTest, HorseAssetPlaysTheSameOnVulkan) {
  const auto paths = testing::horseFrames({1, 9, 17});
  Result<ExampleSet> ex = readObjSequence(paths);
  ASSERT_TRUE(ex.ok()) << ex.status().toString();
  PipelineOptions options;
  options.material = skinMaterial();
  Result<PipelineResult> result = runFitPipeline(*ex, options);
  ASSERT_TRUE(result.ok()) << result.status().toString();
  expectGpuMatchesReference(device(), result->asset);
}

TEST_F(GpuTest, CylinderAssetPlaysTheSameOnVulkan) {
  Result<ExampleSet> ex = testing::cylinderWithRig(true, true);
  ASSERT_TRUE(ex.ok()) << ex.status().toString();
  Result<PipelineResult> result = runFitPipeline(*ex, PipelineOptions{});
  ASSERT_TRUE(result.ok()) << result.status().toString();
  expectGpuMatchesReference(device(), result->asset);
}

}  // namespace
}  // namespace odeskin
