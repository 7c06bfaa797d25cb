// SPDX-License-Identifier: MIT
#include "engine/kernels/fourier_deform_job.hpp"

#include <cmath>
#include <cstring>
#include <numbers>

#include <gtest/gtest.h>

#include "engine/kernels/fourier_deform_fast_job.hpp"
#include "engine/offline/deform_player.hpp"
#include "engine/test_meshes.hpp"

namespace odeskin {
namespace {

// One vertex, one curve, N = 1: small enough to compute the answer by hand.
struct Tiny {
  std::vector<Vec3> rest{Vec3(1.0, 2.0, 3.0)};
  std::vector<CurveBinding> bindings{CurveBinding{0, 0, 0.0, 0.25}};
  std::vector<Vec3> base{Vec3(0.5, 0.0, 0.0)};
  std::vector<std::uint32_t> materials{0};
  // d_0 (constant), d_1 (cos), d_2 (sin), d_3 (trend v)
  std::vector<Vec3> coef{Vec3(1.0, 0.0, 0.0), Vec3(0.0, 7.0, 0.0), Vec3(0.0, 0.0, 2.0), Vec3(4.0, 0.0, 0.0)};
  std::vector<Vec3> rates{Vec3(0.0), Vec3(0.0), Vec3(0.0, 0.0, 1.0), Vec3(0.0)};
  std::vector<ModeBasisValue> basis{{0.5, 0.0}, {2.0, 3.0}, {0.25, 0.0}};  // + remainder weight
  Influences influences;
  std::vector<BoneTransform> bones{BoneTransform(1.0)};
  std::vector<Vec3> out{Vec3(0.0)};

  Tiny() {
    influences.offsets = {0, 1};
    influences.bones = {0};
    influences.weights = {1.0};
  }
  FourierDeformJob job() {
    FourierDeformJob j;
    j.modes = 1;
    j.rest_positions = rest;
    j.bindings = bindings;
    j.base_residuals = base;
    j.curve_materials = materials;
    j.coefficients = coef;
    j.rates = rates;
    j.basis = basis;
    j.influences = InfluencesView(influences);
    j.bones = bones;
    j.out_positions = out;
    return j;
  }
};

TEST(FourierDeformJob, DefaultJobIsInvalid) {
  EXPECT_EQ(FourierDeformJob{}.validate().code(), StatusCode::kOutOfRange);
}

TEST(FourierDeformJob, EachRequiredFieldIsChecked) {
  Tiny t;
  ASSERT_TRUE(t.job().validate().ok()) << t.job().validate().toString();
  auto expectInvalid = [](FourierDeformJob j, const char* what) {
    EXPECT_EQ(j.validate().code(), StatusCode::kInvalidArgument) << what;
  };
  { auto j = t.job(); j.bindings = {}; expectInvalid(j, "bindings"); }
  { auto j = t.job(); j.out_positions = {}; expectInvalid(j, "out_positions"); }
  { auto j = t.job(); j.coefficients = std::span(t.coef).first(3); expectInvalid(j, "coefficients"); }
  { auto j = t.job(); j.rates = std::span(t.rates).first(2); expectInvalid(j, "rates"); }
  { auto j = t.job(); j.basis = {}; expectInvalid(j, "basis"); }
  { auto j = t.job(); j.bones = {}; expectInvalid(j, "bones"); }
  { auto j = t.job(); j.base_residuals = std::span(t.coef).first(2); expectInvalid(j, "base_residuals"); }
  {
    Tiny bad;
    bad.bindings[0].curve_b = 1;
    expectInvalid(bad.job(), "curve index");
  }
  {
    Tiny bad;
    bad.bindings[0].w = 1.5;
    expectInvalid(bad.job(), "blend weight");
  }
  {
    Tiny bad;
    bad.materials[0] = 1;
    expectInvalid(bad.job(), "material index");
  }
  {
    Tiny bad;
    bad.basis[1].gamma = std::nan("");
    expectInvalid(bad.job(), "NaN basis");
  }
  {
    auto j = t.job();
    j.modes = 65;
    EXPECT_EQ(j.validate().code(), StatusCode::kOutOfRange);
  }
}

TEST(FourierDeformJob, HandComputedVertex) {
  Tiny t;
  ASSERT_TRUE(t.job().run().ok());
  // v = 1/4: cos(2 pi v) = 0, sin(2 pi v) = 1, trend v = 0.25.
  // mode 0: 0.5 * (d0 + 0.25 d3) = 0.5 * (2, 0, 0) = (1, 0, 0); rates of mode 0 are zero.
  // mode 1: gamma 2 * (0 * d1 + 1 * d2) = (0, 0, 4); psi 3 * (1 * rate_2) = (0, 0, 3).
  const Vec3 expected = t.rest[0] + t.base[0] + Vec3(1.0, 0.0, 7.0);
  EXPECT_NEAR(t.out[0].x, expected.x, 1e-14);
  EXPECT_NEAR(t.out[0].y, expected.y, 1e-14);
  EXPECT_NEAR(t.out[0].z, expected.z, 1e-14);
}

TEST(FourierDeformJob, PosedResidualIsAddedAfterSkinning) {
  Tiny t;
  RigidTransform turn = rotationAbout(Vec3(0.0), Vec3(0.0, 0.0, 1.0), std::numbers::pi / 2);
  t.bones[0] = turn.matrix();
  auto bind = t.job();
  ASSERT_TRUE(bind.run().ok());
  const Vec3 bind_out = t.out[0];
  auto posed = t.job();
  posed.residual_space = ResidualSpace::kPosed;
  ASSERT_TRUE(posed.run().ok());
  const Vec3 residual = Vec3(0.5, 0.0, 0.0) + Vec3(1.0, 0.0, 7.0);
  const Vec3 expect_bind = turn.apply(t.rest[0] + residual);
  const Vec3 expect_posed = turn.apply(t.rest[0]) + residual;
  EXPECT_LT(glm::length(bind_out - expect_bind), 1e-12);
  EXPECT_LT(glm::length(t.out[0] - expect_posed), 1e-12);
}

TEST(FourierDeformJob, ZeroBasisAndIdentityBonesGiveRestPlusBase) {
  DeformAsset a = testing::randomAsset(300, 7, 5, 4, 3, 2, 11);
  std::vector<ModeBasisValue> basis(2 * 6 + 1);
  std::vector<BoneTransform> bones(4, BoneTransform(1.0));
  std::vector<Vec3> out(300);
  ASSERT_TRUE(referenceJob(a, 0, basis, bones, out).run().ok());
  for (std::size_t i = 0; i < out.size(); ++i) {
    ASSERT_LT(glm::length(out[i] - (a.rest_positions[i] + a.segments[0].base_residuals[i])), 1e-12) << i;
  }
}

TEST(FourierDeformJob, NonFiniteBoneIsInvalid) {
  Tiny t;
  t.bones[0][2][1] = std::nan("");
  const Status s = t.job().validate();
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(s.message(), "fourier deform: bone 0 has a non-finite entry");
}

TEST(FourierDeformJob, UnknownSkinningModeIsInvalid) {
  Tiny t;
  auto j = t.job();
  j.skinning = static_cast<SkinningMode>(7);
  EXPECT_EQ(j.validate().code(), StatusCode::kInvalidArgument);
}

// Kavan et al. 2008, Algorithm 1, written out with quaternion products and nothing from
// dual_quaternion.hpp: the vertex's rigid bones as r_b + eps 1/2 t_b r_b, signs against the
// largest weight, the normalised blend applied as r x r* + 2 vec(d r*).
Vec3 directDqs(const Influences& in, std::span<const BoneTransform> bones, std::size_t i, const Vec3& x) {
  auto real = [&](std::uint32_t b) { return glm::quat_cast(glm::dmat3(bones[b])); };
  auto dual = [&](std::uint32_t b) {
    const Vec3 t = bones[b][3];
    return 0.5 * (glm::dquat(0.0, t.x, t.y, t.z) * real(b));
  };
  std::uint32_t pivot = in.offsets[i];
  for (std::uint32_t k = in.offsets[i]; k < in.offsets[i + 1]; ++k) {
    if (in.weights[k] > in.weights[pivot]) pivot = k;
  }
  glm::dquat r(0.0, 0.0, 0.0, 0.0), d(0.0, 0.0, 0.0, 0.0);
  for (std::uint32_t k = in.offsets[i]; k < in.offsets[i + 1]; ++k) {
    const std::uint32_t b = in.bones[k];
    const double sign = glm::dot(real(b), real(in.bones[pivot])) < 0.0 ? -1.0 : 1.0;
    r += sign * in.weights[k] * real(b);
    d += sign * in.weights[k] * dual(b);
  }
  const double norm = glm::length(r);
  r = r / norm;
  d = d / norm;
  const glm::dquat t = 2.0 * (d * glm::conjugate(r));
  return r * x + Vec3(t.x, t.y, t.z);
}

TEST(FourierDeformJob, DualQuaternionSkinningMatchesTheDirectFormula) {
  for (ResidualSpace space : {ResidualSpace::kBind, ResidualSpace::kPosed}) {
    DeformAsset a = testing::randomAsset(400, 9, 5, 6, 4, 2, 31);
    a.residual_space = space;
    const std::vector<ModeBasisValue> basis = testing::randomBasis(2 * 6 + 1, 17);
    // X + r + D: the job with identity bones in bind space.
    std::vector<BoneTransform> identity(6, BoneTransform(1.0));
    std::vector<Vec3> corrected(a.vertexCount());
    FourierDeformJob rest = referenceJob(a, 1, basis, identity, corrected);
    rest.residual_space = ResidualSpace::kBind;
    ASSERT_TRUE(rest.run().ok());

    const std::vector<BoneTransform> bones = testing::randomBones(6, 23);
    std::vector<Vec3> out(a.vertexCount());
    FourierDeformJob job = referenceJob(a, 1, basis, bones, out);
    job.skinning = SkinningMode::kDualQuaternion;
    ASSERT_TRUE(job.run().ok());
    std::vector<Vec3> lbs(a.vertexCount());
    ASSERT_TRUE(referenceJob(a, 1, basis, bones, lbs).run().ok());
    double worst = 0.0, lbs_gap = 0.0;
    for (std::size_t i = 0; i < out.size(); ++i) {
      const Vec3& x = a.rest_positions[i];
      const Vec3 expected = space == ResidualSpace::kBind ? directDqs(a.influences, bones, i, corrected[i])
                                                          : directDqs(a.influences, bones, i, x) + (corrected[i] - x);
      worst = std::max(worst, glm::length(out[i] - expected));
      lbs_gap = std::max(lbs_gap, glm::length(lbs[i] - expected));
    }
    EXPECT_LT(worst, 1e-12) << (space == ResidualSpace::kBind ? "bind" : "posed");
    // The modes really differ on these bones (up to 57 degrees apart), so the check above can fail.
    EXPECT_GT(lbs_gap, 1e-2);
  }
}

TEST(FourierDeformJob, BlendIsLinearInW) {
  // Moving w from 0 to 1 moves the vertex linearly from curve a's series to curve b's.
  DeformAsset a = testing::randomAsset(1, 2, 3, 1, 1, 1, 5);
  a.bindings[0] = CurveBinding{0, 1, 0.0, 0.3};
  std::vector<ModeBasisValue> basis = testing::randomBasis(4 + 1, 9);
  std::vector<BoneTransform> bones(1, BoneTransform(1.0));
  Vec3 out[3];
  const double ws[3] = {0.0, 1.0, 0.25};
  for (int k = 0; k < 3; ++k) {
    a.bindings[0].w = ws[k];
    ASSERT_TRUE(referenceJob(a, 1, basis, bones, std::span(&out[k], 1)).run().ok());
  }
  EXPECT_LT(glm::length(out[2] - (0.75 * out[0] + 0.25 * out[1])), 1e-12);
}

// The fast path follows the shader in float32; against the double reference its error is a few
// float ulps of the largest term, so 2e-5 absolute on unit-size data leaves a wide margin while a
// wrong index or sign (errors of 1e-2 and more) cannot pass.
void expectFastMatchesReference(std::uint32_t layout, ResidualSpace space, unsigned threads,
                                SkinningMode skinning = SkinningMode::kLinear) {
  DeformAsset a = testing::randomAsset(5000, 40, 9, 12, layout == 0 ? 7 : layout, 3, 21);
  a.residual_space = space;
  a.skinning = skinning;
  Result<PackedDeformData> packed = packDeformAsset(a, layout);
  ASSERT_TRUE(packed.ok()) << packed.status().toString();
  const std::vector<ModeBasisValue> basis = testing::randomBasis(3 * 10 + 1, 3);
  const std::vector<BoneTransform> bones = testing::randomBones(12, 4);
  for (std::uint32_t segment = 0; segment < 2; ++segment) {
    std::vector<Vec3> expected(a.vertexCount());
    FourierDeformJob reference = referenceJob(a, segment, basis, bones, expected);
    reference.skinning = skinning;
    ASSERT_TRUE(reference.run().ok());
    std::vector<gpu::BoneMatrix> gpu_bones(12);
    std::vector<gpu::ModeBasis> gpu_basis(basis.size());
    toGpuBones(bones, gpu_bones);
    toGpuBasis(basis, gpu_basis);
    std::vector<gpu::Float4> out(a.vertexCount());
    FourierDeformFastJob job{&*packed, segment, gpu_bones, gpu_basis, out, threads};
    ASSERT_TRUE(job.run().ok());
    double worst = 0.0;
    std::size_t worst_i = 0;
    for (std::size_t i = 0; i < out.size(); ++i) {
      const double e = glm::length(Vec3(out[i].x, out[i].y, out[i].z) - expected[i]);
      if (e > worst) { worst = e; worst_i = i; }
    }
    EXPECT_LT(worst, 2e-5) << "layout " << layout << " segment " << segment << " worst vertex " << worst_i;
  }
}

TEST(FourierDeformFastJob, MatchesReferenceSparseBind) { expectFastMatchesReference(0, ResidualSpace::kBind, 1); }
TEST(FourierDeformFastJob, MatchesReferenceFourSlots) { expectFastMatchesReference(4, ResidualSpace::kBind, 0); }
TEST(FourierDeformFastJob, MatchesReferenceEightSlotsPosed) { expectFastMatchesReference(8, ResidualSpace::kPosed, 2); }
TEST(FourierDeformFastJob, DualQuaternionMatchesReferenceSparseBind) {
  expectFastMatchesReference(0, ResidualSpace::kBind, 1, SkinningMode::kDualQuaternion);
}
TEST(FourierDeformFastJob, DualQuaternionMatchesReferenceFourSlotsPosed) {
  expectFastMatchesReference(4, ResidualSpace::kPosed, 0, SkinningMode::kDualQuaternion);
}
TEST(FourierDeformFastJob, DualQuaternionMatchesReferenceEightSlots) {
  expectFastMatchesReference(8, ResidualSpace::kBind, 2, SkinningMode::kDualQuaternion);
}

TEST(FourierDeformFastJob, BitIdenticalAcrossThreadCounts) {
  for (SkinningMode skinning : {SkinningMode::kLinear, SkinningMode::kDualQuaternion}) {
    DeformAsset a = testing::randomAsset(20000, 30, 9, 8, 5, 2, 8);
    a.skinning = skinning;
    Result<PackedDeformData> packed = packDeformAsset(a, 0);
    ASSERT_TRUE(packed.ok());
    std::vector<gpu::BoneMatrix> bones(8);
    toGpuBones(testing::randomBones(8, 1), bones);
    std::vector<gpu::ModeBasis> basis(21);
    toGpuBasis(testing::randomBasis(21, 2), basis);
    std::vector<gpu::Float4> one(a.vertexCount()), many(a.vertexCount());
    ASSERT_TRUE((FourierDeformFastJob{&*packed, 1, bones, basis, one, 1}).run().ok());
    ASSERT_TRUE((FourierDeformFastJob{&*packed, 1, bones, basis, many, 0}).run().ok());
    EXPECT_EQ(0, std::memcmp(one.data(), many.data(), one.size() * sizeof(gpu::Float4)));
  }
}

TEST(FourierDeformFastJob, ValidatesSizes) {
  DeformAsset a = testing::randomAsset(10, 2, 3, 2, 2, 1, 1);
  Result<PackedDeformData> packed = packDeformAsset(a, 0);
  ASSERT_TRUE(packed.ok());
  std::vector<gpu::BoneMatrix> bones(2);
  std::vector<gpu::ModeBasis> basis(5);
  std::vector<gpu::Float4> out(10);
  EXPECT_TRUE((FourierDeformFastJob{&*packed, 0, bones, basis, out, 1}).validate().ok());
  EXPECT_EQ((FourierDeformFastJob{}).validate().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ((FourierDeformFastJob{&*packed, 2, bones, basis, out, 1}).validate().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ((FourierDeformFastJob{&*packed, 0, std::span(bones).first(1), basis, out, 1}).validate().code(),
            StatusCode::kInvalidArgument);
  EXPECT_EQ((FourierDeformFastJob{&*packed, 0, bones, std::span(basis).first(4), out, 1}).validate().code(),
            StatusCode::kInvalidArgument);
  EXPECT_EQ((FourierDeformFastJob{&*packed, 0, bones, basis, std::span(out).first(9), 1}).validate().code(),
            StatusCode::kInvalidArgument);
  packed->skinning = static_cast<SkinningMode>(2);
  EXPECT_EQ((FourierDeformFastJob{&*packed, 0, bones, basis, out, 1}).validate().code(), StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace odeskin
