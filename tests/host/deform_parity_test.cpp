// SPDX-License-Identifier: MIT
// CPU reference vs Vulkan on a realistic asset: the procedural arm at 204,800 vertices, N = 9, three
// keys (so segment 1 carries rates), three materials (dynamic skin, static, a stiffening bending
// material), at times that include both ends of each segment, with linear blend and with
// dual-quaternion skinning. Issue requirement: max |GPU - CPU reference| <= 1e-5 x bounding-box
// diagonal.
#include <algorithm>
#include <cstdio>

#include <gtest/gtest.h>

#include "engine/kernels/fourier_deform_fast_job.hpp"
#include "engine/offline/deform_player.hpp"
#include "engine/offline/procedural_arm.hpp"
#include "host/gpu_deformer.hpp"
#include "host/gpu_test_support.hpp"

namespace odeskin {
namespace {

constexpr double kRelativeTolerance = 1e-5;

struct Fixture {
  DeformAsset asset;
  PackedDeformData packed;
};

Result<Fixture> bigArm() {
  ArmOptions o;
  o.rings = 3200;
  o.ring_vertices = 64;
  o.bend_degrees = 60.0;
  o.bulge = 0.2;
  ODESKIN_ASSIGN_OR_RETURN(ProceduralArm first, makeProceduralArm(o));
  o.bend_degrees = 120.0;
  o.bulge = 0.4;
  ODESKIN_ASSIGN_OR_RETURN(ProceduralArm second, makeProceduralArm(o));
  FitInput in = std::move(first.fit_input);
  in.poses.push_back(second.end_positions);
  in.key_poses.push_back(second.fit_input.key_poses[1]);
  FitOptions fit;
  fit.modes = 9;
  fit.materials = {skinMaterial(), staticMaterial(), Material{1.0, 4.0, 60.0, 0.05, BendingSign::kStiffening}};
  for (std::size_t c = 0; c < in.curves.size(); ++c) fit.curve_materials.push_back(static_cast<std::uint32_t>(c % 3));
  Fixture f;
  ODESKIN_ASSIGN_OR_RETURN(f.asset, fitDeformAsset(in, fit));
  ODESKIN_ASSIGN_OR_RETURN(f.packed, packDeformAsset(f.asset));
  return f;
}

double boxDiagonal(std::span<const Vec3> p) {
  Vec3 lo(1e300), hi(-1e300);
  for (const Vec3& x : p) {
    lo = glm::min(lo, x);
    hi = glm::max(hi, x);
  }
  return glm::length(hi - lo);
}

class DeformParity : public testing::GpuTest {
 protected:
  // Plays `asset` (packed as `packed`) on the reference, the fast path and the GPU.
  void expectParity(const DeformAsset& asset, const PackedDeformData& packed) {
    Result<DeformPlayer> player = DeformPlayer::create(asset);
    ASSERT_TRUE(player.ok());
    Result<GpuDeformer> gpu = GpuDeformer::create(device(), packed);
    ASSERT_TRUE(gpu.ok()) << gpu.status().toString();
    const char* mode = asset.skinning == SkinningMode::kDualQuaternion ? "dqs" : "lbs";

    std::vector<ModeBasisValue> basis(player->basisSize());
    std::vector<BoneTransform> bones(asset.bone_count);
    std::vector<gpu::ModeBasis> gpu_basis(basis.size());
    std::vector<gpu::BoneMatrix> gpu_bones(bones.size());
    std::vector<Vec3> expected(asset.vertexCount());
    std::vector<gpu::Float4> actual(asset.vertexCount());
    std::vector<gpu::Float4> fast(asset.vertexCount());
    // Segment ends are played from both sides (segment 0 at tau = 1 and segment 1 at tau = 0).
    const std::pair<std::uint32_t, double> frames[] = {{0, 0.0}, {0, 0.37}, {0, 1.0}, {1, 0.0}, {1, 0.5}, {1, 1.0}};
    for (const auto& [segment, tau] : frames) {
      player->basisAt(tau, basis);
      player->bonesAt(asset, segment, tau, bones);
      FourierDeformJob reference = referenceJob(asset, segment, basis, bones, expected);
      reference.skinning = asset.skinning;
      ASSERT_TRUE(reference.run().ok());
      toGpuBasis(basis, gpu_basis);
      toGpuBones(bones, gpu_bones);
      ASSERT_TRUE(gpu->run(GpuDeformFrame{segment, gpu_bones, gpu_basis}).ok());
      ASSERT_TRUE(gpu->readPositions(actual).ok());
      ASSERT_TRUE((FourierDeformFastJob{&packed, segment, gpu_bones, gpu_basis, fast, 0}).run().ok());
      const double limit = kRelativeTolerance * boxDiagonal(expected);
      double worst_gpu = 0.0, worst_fast = 0.0;
      std::size_t worst_i = 0;
      for (std::size_t i = 0; i < expected.size(); ++i) {
        const double e = glm::length(Vec3(actual[i].x, actual[i].y, actual[i].z) - expected[i]);
        if (e > worst_gpu) {
          worst_gpu = e;
          worst_i = i;
        }
        worst_fast = std::max(worst_fast, glm::length(Vec3(fast[i].x, fast[i].y, fast[i].z) - expected[i]));
      }
      EXPECT_LE(worst_gpu, limit) << mode << " segment " << segment << " tau " << tau << " worst vertex " << worst_i
                                  << " expected (" << expected[worst_i].x << ", " << expected[worst_i].y << ", "
                                  << expected[worst_i].z << ") got (" << actual[worst_i].x << ", "
                                  << actual[worst_i].y << ", " << actual[worst_i].z << ")";
      EXPECT_LE(worst_fast, limit) << "CPU fast path, " << mode << " segment " << segment << " tau " << tau;
      std::printf("%s segment %u tau %.2f: max |gpu - ref| = %.3e, max |fast - ref| = %.3e (limit %.3e)\n", mode,
                  segment, tau, worst_gpu, worst_fast, limit);
    }
  }
};

TEST_F(DeformParity, ArmAt200kVerticesMatchesTheReference) {
  Result<Fixture> fixture = bigArm();
  ASSERT_TRUE(fixture.ok()) << fixture.status().toString();
  ASSERT_GE(fixture->asset.vertexCount(), 200000u);
  ASSERT_FALSE(fixture->packed.rates.empty()) << "segment 1 should carry rates";
  expectParity(fixture->asset, fixture->packed);
}

// The same fitted asset played with dual-quaternion skinning (its residuals were fitted for LBS, so
// this checks the deformer, not the fit). The arm's two bones turn up to 120 degrees at the elbow,
// where DQS and LBS differ most.
TEST_F(DeformParity, ArmAt200kVerticesWithDualQuaternionsMatchesTheReference) {
  Result<Fixture> fixture = bigArm();
  ASSERT_TRUE(fixture.ok()) << fixture.status().toString();
  fixture->asset.skinning = SkinningMode::kDualQuaternion;
  Result<PackedDeformData> packed = packDeformAsset(fixture->asset);
  ASSERT_TRUE(packed.ok()) << packed.status().toString();
  ASSERT_EQ(packed->skinning, SkinningMode::kDualQuaternion);
  expectParity(fixture->asset, *packed);
}

}  // namespace
}  // namespace odeskin
