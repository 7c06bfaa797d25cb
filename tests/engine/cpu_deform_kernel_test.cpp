// SPDX-License-Identifier: MIT
// CpuDeformKernel against the double reference (FourierDeformJob) and the float fast path
// (FourierDeformFastJob) on random and fitted assets, for every instruction set this CPU runs.
// Tolerance: 1e-5 of the bounding box's longest side. The kernel is float32 like the fast path;
// its error against the reference is a few float ulps of the largest term (~1e-7 of the box on
// these data), while a wrong index, sign or lane (errors of 1e-3 of the box and more) cannot pass.
#include "engine/kernels/cpu_deform_kernel.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <optional>
#include <string>

#include <gtest/gtest.h>

#include "engine/kernels/fourier_deform_fast_job.hpp"
#include "engine/kernels/lbs_job.hpp"
#include "engine/offline/deform_player.hpp"
#include "engine/offline/procedural_arm.hpp"
#include "engine/offline/residual_fit.hpp"
#include "engine/random_packed_data.hpp"
#include "engine/test_meshes.hpp"

namespace odeskin {
namespace {

constexpr double kRelativeTolerance = 1e-5;

// Synthetic packed data in the GPU layout (no fit), larger than the GPU test's: random curve pairs
// in either order, w anywhere in [0, 1] (0 and 1 included), 1 to 6 influences per vertex, sparse
// remainders on a third of the vertices except in segment 1, every third curve stopping at n = 2,
// and affine bones near the identity.
testing::RandomPackedOptions packedOptions() {
  testing::RandomPackedOptions o;
  o.modes = 9;
  o.curve_count = 23;
  o.segment_count = 3;
  o.w_edge_cases = true;
  o.segment_without_remainders = 1;
  o.truncate_every_third_curve = true;
  return o;
}

double worstError(std::span<const Vec3> expected, std::span<const gpu::Float4> actual, std::size_t* where = nullptr) {
  double worst = 0.0;
  for (std::size_t i = 0; i < expected.size(); ++i) {
    double e = glm::length(Vec3(actual[i].x, actual[i].y, actual[i].z) - expected[i]);
    if (!(e == e)) e = 1e300;  // NaN fails
    if (actual[i].w != 1.0f) e = 1e300;
    if (e > worst) {
      worst = e;
      if (where) *where = i;
    }
  }
  return worst;
}

std::vector<Vec3> toVec3(std::span<const gpu::Float4> p) {
  std::vector<Vec3> out;
  for (const gpu::Float4& f : p) out.emplace_back(f.x, f.y, f.z);
  return out;
}

// Bit-for-bit equality (NaNs and signed zeros included). memcmp is undefined for a null pointer even
// with length 0, and an empty vector's data() may be null (UBSan stopped the V = 0 case here).
bool bitIdentical(std::span<const gpu::Float4> a, std::span<const gpu::Float4> b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size_bytes()) == 0);
}

std::string describe(CpuKernelArch arch, std::uint32_t layout, ResidualSpace space, SkinningMode skinning) {
  return std::string(cpuKernelArchName(arch)) + " layout " + std::to_string(layout) +
         (space == ResidualSpace::kBind ? " bind" : " posed") +
         (skinning == SkinningMode::kDualQuaternion ? " dqs" : " lbs");
}

// A random asset whose even curves have no harmonic above 3 in segment 0 (so two-curve blocks mix
// curves that stop at different modes) and, optionally, no rates at all.
DeformAsset testAsset(std::size_t vertices, std::uint32_t layout, ResidualSpace space, SkinningMode skinning,
                      bool rates, unsigned seed) {
  DeformAsset a = testing::randomAsset(vertices, 40, 9, 12, layout == 0 ? 7 : layout, 3, seed);
  a.residual_space = space;
  a.skinning = skinning;
  const std::size_t m_count = coefficientsPerCurve(a.modes);
  for (std::size_t c = 0; c < 40; c += 2) {
    for (std::size_t m = 7; m + 1 < m_count; ++m) a.segments[0].coefficients[c * m_count + m] = Vec3(0.0);
  }
  if (!rates) {
    for (DeformSegment& s : a.segments) std::fill(s.rates.begin(), s.rates.end(), Vec3(0.0));
  }
  return a;
}

struct Frame {
  std::vector<ModeBasisValue> basis;
  std::vector<BoneTransform> bones;
  std::vector<gpu::ModeBasis> gpu_basis;
  std::vector<gpu::BoneMatrix> gpu_bones;
};

Frame randomFrame(const DeformAsset& a, unsigned seed) {
  Frame f;
  f.basis = testing::randomBasis(a.materials.size() * (a.modes + 1) + 1, seed);
  f.bones = testing::randomBones(a.bone_count, seed + 1);
  f.gpu_basis.resize(f.basis.size());
  f.gpu_bones.resize(f.bones.size());
  toGpuBasis(f.basis, f.gpu_basis);
  toGpuBones(f.bones, f.gpu_bones);
  return f;
}

// Every segment, threads 1 and 2 (bit-identical), against the reference and the fast path.
void expectMatches(const DeformAsset& a, const PackedDeformData& packed, const Frame& f, CpuKernelArch arch,
                   const std::string& what) {
  Result<CpuDeformKernel> kernel = CpuDeformKernel::create(packed, arch);
  ASSERT_TRUE(kernel.ok()) << kernel.status().toString();
  ASSERT_EQ(kernel->vertexCount(), a.vertexCount());
  for (std::uint32_t segment = 0; segment < a.segments.size(); ++segment) {
    std::vector<Vec3> expected(a.vertexCount());
    ASSERT_TRUE(referenceJob(a, segment, f.basis, f.bones, expected).run().ok());
    // At least 1: one vertex has no box, and every asset here spans about 1 to 3 units.
    const double box = std::max(longestBoxSide(expected), 1.0);
    std::vector<gpu::Float4> fast(a.vertexCount());
    ASSERT_TRUE((FourierDeformFastJob{&packed, segment, f.gpu_bones, f.gpu_basis, fast, 1}).run().ok());
    std::vector<gpu::Float4> one(a.vertexCount(), gpu::Float4{9, 9, 9, 9});
    std::vector<gpu::Float4> two(a.vertexCount(), gpu::Float4{7, 7, 7, 7});
    ASSERT_TRUE(kernel->deform(segment, f.gpu_bones, f.gpu_basis, one, 1).ok());
    ASSERT_TRUE(kernel->deform(segment, f.gpu_bones, f.gpu_basis, two, 2).ok());
    std::size_t worst_i = 0;
    const double vs_reference = worstError(expected, one, &worst_i) / box;
    EXPECT_LT(vs_reference, kRelativeTolerance) << what << " segment " << segment << " vertex " << worst_i;
    EXPECT_LT(worstError(toVec3(fast), one) / box, kRelativeTolerance) << what << " vs fast, segment " << segment;
    EXPECT_TRUE(bitIdentical(one, two)) << what << " threads";
  }
}

class CpuDeformKernelArchs : public ::testing::TestWithParam<CpuKernelArch> {};

TEST_P(CpuDeformKernelArchs, MatchesReferenceEveryLayoutSpaceAndSkinning) {
  for (std::uint32_t layout : {0u, 4u, 8u}) {
    for (ResidualSpace space : {ResidualSpace::kBind, ResidualSpace::kPosed}) {
      for (SkinningMode skinning : {SkinningMode::kLinear, SkinningMode::kDualQuaternion}) {
        const DeformAsset a = testAsset(1500, layout, space, skinning, true, 21 + layout);
        Result<PackedDeformData> packed = packDeformAsset(a, layout);
        ASSERT_TRUE(packed.ok()) << packed.status().toString();
        expectMatches(a, *packed, randomFrame(a, 3 + layout), GetParam(), describe(GetParam(), layout, space, skinning));
      }
    }
  }
}

TEST_P(CpuDeformKernelArchs, MatchesReferenceWithoutRates) {
  for (SkinningMode skinning : {SkinningMode::kLinear, SkinningMode::kDualQuaternion}) {
    const DeformAsset a = testAsset(700, 4, ResidualSpace::kBind, skinning, false, 5);
    Result<PackedDeformData> packed = packDeformAsset(a, 4);
    ASSERT_TRUE(packed.ok());
    packed->rates.clear();  // the fast path's "no rates buffer"
    expectMatches(a, *packed, randomFrame(a, 8), GetParam(), "no rates");
  }
}

// Vertex counts that are not multiples of any vector width or of the 16-lane block.
TEST_P(CpuDeformKernelArchs, OddVertexCounts) {
  for (std::size_t v : {0u, 1u, 7u, 17u, 33u, 100u}) {
    for (SkinningMode skinning : {SkinningMode::kLinear, SkinningMode::kDualQuaternion}) {
      const DeformAsset a = testAsset(v, 0, ResidualSpace::kPosed, skinning, true, 30 + static_cast<unsigned>(v));
      Result<PackedDeformData> packed = packDeformAsset(a, 0);
      ASSERT_TRUE(packed.ok());
      expectMatches(a, *packed, randomFrame(a, 4), GetParam(), "V = " + std::to_string(v));
    }
  }
}

// Synthetic packed data (random pairs in either order, w anywhere in [0, 1], affine bones): the
// kernel against FourierDeformFastJob directly.
TEST_P(CpuDeformKernelArchs, MatchesFastPathOnRandomPackedData) {
  for (std::uint32_t layout : {0u, 4u, 8u}) {
    for (SkinningMode skinning : {SkinningMode::kLinear, SkinningMode::kDualQuaternion}) {
      for (bool rates : {true, false}) {
        testing::RandomPackedOptions o = packedOptions();
        o.vertex_count = 537;
        o.influence_layout = layout;
        o.residual_space = layout == 4 ? ResidualSpace::kPosed : ResidualSpace::kBind;
        o.rates = rates;
        o.skinning = skinning;
        o.seed = 11 + layout;
        const PackedDeformData d = testing::randomPackedData(o);
        const std::vector<gpu::BoneMatrix> bones = testing::randomGpuBones(d.bone_count, 2);
        const std::vector<gpu::ModeBasis> basis = testing::randomGpuBasis(ODESKIN_BASIS_ENTRIES(d.material_count, d.modes), 3);
        Result<CpuDeformKernel> kernel = CpuDeformKernel::create(d, GetParam());
        ASSERT_TRUE(kernel.ok()) << kernel.status().toString();
        for (std::uint32_t segment = 0; segment < d.segment_count; ++segment) {
          std::vector<gpu::Float4> fast(d.vertex_count), out(d.vertex_count);
          ASSERT_TRUE((FourierDeformFastJob{&d, segment, bones, basis, fast, 1}).run().ok());
          ASSERT_TRUE(kernel->deform(segment, bones, basis, out, 1).ok());
          const std::vector<Vec3> expected = toVec3(fast);
          EXPECT_LT(worstError(expected, out) / longestBoxSide(expected), kRelativeTolerance)
              << describe(GetParam(), layout, o.residual_space, skinning) << (rates ? " rates" : " no rates");
        }
      }
    }
  }
}

TEST_P(CpuDeformKernelArchs, SkinMatchesLbsFastJobAndReference) {
  for (SkinningMode skinning : {SkinningMode::kLinear, SkinningMode::kDualQuaternion}) {
    for (std::uint32_t layout : {0u, 4u, 8u}) {
      const DeformAsset a = testAsset(999, layout, ResidualSpace::kBind, skinning, true, 40);
      Result<PackedDeformData> packed = packDeformAsset(a, layout);
      ASSERT_TRUE(packed.ok());
      const Frame f = randomFrame(a, 6);
      Result<CpuDeformKernel> kernel = CpuDeformKernel::create(*packed, GetParam());
      ASSERT_TRUE(kernel.ok());
      std::vector<gpu::Float4> fast(a.vertexCount()), out(a.vertexCount()), two(a.vertexCount());
      ASSERT_TRUE((LbsFastJob{&*packed, f.gpu_bones, fast, 1}).run().ok());
      ASSERT_TRUE(kernel->skin(f.gpu_bones, out, 1).ok());
      ASSERT_TRUE(kernel->skin(f.gpu_bones, two, 2).ok());
      const std::vector<Vec3> expected = toVec3(fast);
      const double box = longestBoxSide(expected);
      EXPECT_LT(worstError(expected, out) / box, kRelativeTolerance) << describe(GetParam(), layout, {}, skinning);
      EXPECT_TRUE(bitIdentical(out, two));
      if (skinning == SkinningMode::kLinear) {
        std::vector<Vec3> reference(a.vertexCount());
        ASSERT_TRUE((LbsJob{a.rest_positions, InfluencesView(a.influences), f.bones, reference}).run().ok());
        EXPECT_LT(worstError(reference, out) / box, kRelativeTolerance);
      }
    }
  }
}

// A fitted asset: the procedural arm with three materials (one static), two segments (so segment 1
// carries rates), played at several times, as the runtime will.
TEST_P(CpuDeformKernelArchs, MatchesReferenceOnFittedArm) {
  ArmOptions o;
  o.rings = 40;
  o.ring_vertices = 24;
  Result<ProceduralArm> first = makeProceduralArm(o);
  ASSERT_TRUE(first.ok());
  o.bend_degrees = 130.0;
  o.bulge = 0.5;
  Result<ProceduralArm> second = makeProceduralArm(o);
  ASSERT_TRUE(second.ok());
  FitInput in = std::move(first->fit_input);
  in.poses.push_back(second->end_positions);
  in.key_poses.push_back(second->fit_input.key_poses[1]);
  for (ResidualSpace space : {ResidualSpace::kBind, ResidualSpace::kPosed}) {
    for (SkinningMode skinning : {SkinningMode::kLinear, SkinningMode::kDualQuaternion}) {
      FitOptions fit;
      fit.modes = 9;
      fit.residual_space = space;
      fit.skinning = skinning;
      fit.materials = {skinMaterial(), staticMaterial(), Material{1.0, 4.0, 60.0, 0.05, BendingSign::kStiffening}};
      for (std::size_t c = 0; c < in.curves.size(); ++c) fit.curve_materials.push_back(static_cast<std::uint32_t>(c % 3));
      Result<DeformAsset> a = fitDeformAsset(in, fit);
      ASSERT_TRUE(a.ok()) << a.status().toString();
      Result<PackedDeformData> packed = packDeformAsset(*a, 4);
      ASSERT_TRUE(packed.ok());
      Result<DeformPlayer> player = DeformPlayer::create(*a);
      ASSERT_TRUE(player.ok());
      Result<CpuDeformKernel> kernel = CpuDeformKernel::create(*packed, GetParam());
      ASSERT_TRUE(kernel.ok());
      Frame f;
      f.basis.resize(player->basisSize());
      f.bones.resize(a->bone_count);
      f.gpu_basis.resize(f.basis.size());
      f.gpu_bones.resize(f.bones.size());
      for (double t : {0.0, 0.37, 1.0, 1.5, 2.0}) {
        const auto [segment, tau] = player->locate(t);
        player->basisAt(tau, f.basis);
        player->bonesAt(*a, segment, tau, f.bones);
        toGpuBasis(f.basis, f.gpu_basis);
        toGpuBones(f.bones, f.gpu_bones);
        std::vector<Vec3> expected(a->vertexCount());
        ASSERT_TRUE(referenceJob(*a, segment, f.basis, f.bones, expected).run().ok());
        std::vector<gpu::Float4> out(a->vertexCount());
        ASSERT_TRUE(kernel->deform(segment, f.gpu_bones, f.gpu_basis, out, 1).ok());
        EXPECT_LT(worstError(expected, out) / longestBoxSide(expected), kRelativeTolerance)
            << describe(GetParam(), 4, space, skinning) << " t = " << t;
      }
    }
  }
}

TEST_P(CpuDeformKernelArchs, CallerDualQuaternionsGiveTheSameFrame) {
  const DeformAsset a = testAsset(300, 8, ResidualSpace::kBind, SkinningMode::kDualQuaternion, true, 50);
  Result<PackedDeformData> packed = packDeformAsset(a, 8);
  ASSERT_TRUE(packed.ok());
  const Frame f = randomFrame(a, 9);
  Result<CpuDeformKernel> kernel = CpuDeformKernel::create(*packed, GetParam());
  ASSERT_TRUE(kernel.ok());
  std::vector<gpu::DualQuat> dual_quats(a.bone_count);
  toGpuDualQuaternions(f.gpu_bones, dual_quats);
  std::vector<gpu::Float4> inside(a.vertexCount()), given(a.vertexCount());
  ASSERT_TRUE(kernel->deform(1, f.gpu_bones, f.gpu_basis, inside).ok());
  ASSERT_TRUE(kernel->deform(1, f.gpu_bones, dual_quats, f.gpu_basis, given).ok());
  EXPECT_TRUE(bitIdentical(inside, given));
  ASSERT_TRUE(kernel->skin(f.gpu_bones, inside).ok());
  ASSERT_TRUE(kernel->skin(f.gpu_bones, dual_quats, given).ok());
  EXPECT_TRUE(bitIdentical(inside, given));
  EXPECT_EQ(kernel->deform(1, f.gpu_bones, std::span(dual_quats).first(3), f.gpu_basis, given).code(),
            StatusCode::kInvalidArgument);
}

// A vertex without weight has no dual-quaternion blend: it takes the LBS result (the origin), as
// the fast path does, and its neighbours in the block are unaffected.
TEST_P(CpuDeformKernelArchs, DegenerateDualQuaternionBlendFallsBackToLbs) {
  testing::RandomPackedOptions o = packedOptions();
  o.vertex_count = 40;
  o.influence_layout = 4;
  o.skinning = SkinningMode::kDualQuaternion;
  PackedDeformData d = testing::randomPackedData(o);
  for (std::uint32_t k = 0; k < 4; ++k) d.influences[5 * 4 + k].weight = 0.0f;
  const std::vector<gpu::BoneMatrix> bones = testing::randomGpuBones(d.bone_count, 2);
  Result<CpuDeformKernel> kernel = CpuDeformKernel::create(d, GetParam());
  ASSERT_TRUE(kernel.ok());
  std::vector<gpu::Float4> fast(d.vertex_count), out(d.vertex_count);
  ASSERT_TRUE((LbsFastJob{&d, bones, fast, 1}).run().ok());
  ASSERT_TRUE(kernel->skin(bones, out).ok());
  EXPECT_EQ(out[5].x, 0.0f);
  EXPECT_EQ(out[5].y, 0.0f);
  EXPECT_EQ(out[5].z, 0.0f);
  const std::vector<Vec3> expected = toVec3(fast);
  EXPECT_LT(worstError(expected, out) / longestBoxSide(expected), kRelativeTolerance);
}

std::string archName(const ::testing::TestParamInfo<CpuKernelArch>& info) { return cpuKernelArchName(info.param); }

INSTANTIATE_TEST_SUITE_P(Supported, CpuDeformKernelArchs, ::testing::ValuesIn(supportedCpuKernelArchs()), archName);

TEST(CpuDeformKernel, EveryInstructionSetGivesNearlyTheSameFrame) {
  const DeformAsset a = testAsset(2000, 0, ResidualSpace::kBind, SkinningMode::kLinear, true, 60);
  Result<PackedDeformData> packed = packDeformAsset(a, 0);
  ASSERT_TRUE(packed.ok());
  const Frame f = randomFrame(a, 10);
  std::vector<gpu::Float4> generic(a.vertexCount()), other(a.vertexCount());
  Result<CpuDeformKernel> base = CpuDeformKernel::create(*packed, CpuKernelArch::kGeneric);
  ASSERT_TRUE(base.ok());
  ASSERT_TRUE(base->deform(1, f.gpu_bones, f.gpu_basis, generic).ok());
  const std::vector<Vec3> expected = toVec3(generic);
  for (CpuKernelArch arch : supportedCpuKernelArchs()) {
    Result<CpuDeformKernel> kernel = CpuDeformKernel::create(*packed, arch);
    ASSERT_TRUE(kernel.ok());
    EXPECT_EQ(kernel->arch(), arch);
    ASSERT_TRUE(kernel->deform(1, f.gpu_bones, f.gpu_basis, other).ok());
    // Only FMA contraction differs between them.
    EXPECT_LT(worstError(expected, other) / longestBoxSide(expected), 1e-6) << cpuKernelArchName(arch);
  }
  EXPECT_EQ(supportedCpuKernelArchs().back(), CpuKernelArch::kGeneric);
}

TEST(CpuDeformKernel, TheFastestSupportedSetIsTheDefault) {
  const PackedDeformData d = testing::randomPackedData(packedOptions());
  Result<CpuDeformKernel> kernel = CpuDeformKernel::create(d);
  ASSERT_TRUE(kernel.ok());
  if (std::getenv("ODESKIN_CPU_KERNEL_ARCH") == nullptr) {
    EXPECT_EQ(kernel->arch(), supportedCpuKernelArchs().front());
  }
}

// A misspelt cap is an error, not ignored (a benchmark would time the wrong kernel). The
// environment changes while no other thread of the test reads it, hence the NOLINTs.
TEST(CpuDeformKernel, AnUnknownInstructionSetCapIsAnError) {
  const PackedDeformData d = testing::randomPackedData(packedOptions());
  std::optional<std::string> old;
  if (const char* value = std::getenv("ODESKIN_CPU_KERNEL_ARCH")) old = value;
  setenv("ODESKIN_CPU_KERNEL_ARCH", "AVX-512", 1);  // NOLINT(concurrency-mt-unsafe)
  Result<CpuDeformKernel> kernel = CpuDeformKernel::create(d);
  setenv("ODESKIN_CPU_KERNEL_ARCH", "generic", 1);  // NOLINT(concurrency-mt-unsafe)
  Result<CpuDeformKernel> generic = CpuDeformKernel::create(d);
  if (old) setenv("ODESKIN_CPU_KERNEL_ARCH", old->c_str(), 1);  // NOLINT(concurrency-mt-unsafe)
  else unsetenv("ODESKIN_CPU_KERNEL_ARCH");                       // NOLINT(concurrency-mt-unsafe)
  ASSERT_FALSE(kernel.ok());
  EXPECT_EQ(kernel.status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(kernel.status().message(), "ODESKIN_CPU_KERNEL_ARCH=AVX-512: expected generic, avx2 or avx512");
  ASSERT_TRUE(generic.ok());
  EXPECT_EQ(generic->arch(), CpuKernelArch::kGeneric);
}

// The arm's rings share their curve pair and its two bones: no padding, one or two bones a block.
TEST(CpuDeformKernel, ArmBlocksAreFullAndShareBones) {
  ArmOptions o;
  o.rings = 21;
  o.ring_vertices = 32;
  Result<ProceduralArm> arm = makeProceduralArm(o);
  ASSERT_TRUE(arm.ok());
  FitOptions fit;
  fit.modes = 5;
  Result<DeformAsset> a = fitDeformAsset(arm->fit_input, fit);
  ASSERT_TRUE(a.ok()) << a.status().toString();
  Result<PackedDeformData> packed = packDeformAsset(*a, 4);
  ASSERT_TRUE(packed.ok());
  Result<CpuDeformKernel> kernel = CpuDeformKernel::create(*packed);
  ASSERT_TRUE(kernel.ok());
  const CpuDeformKernel::Stats s = kernel->stats();
  EXPECT_EQ(s.lanes, a->vertexCount());  // rings of 32: no padding on any instruction set
  EXPECT_EQ(s.blocks * 16, s.lanes);
  EXPECT_GT(s.two_curve_blocks, 0u);
  EXPECT_LE(s.mean_union_bones, 2.0);
  EXPECT_GT(s.bytes, a->vertexCount() * 7 * sizeof(float));
}

TEST(CpuDeformKernel, PerFrameInputsAreValidated) {
  const DeformAsset a = testAsset(10, 0, ResidualSpace::kBind, SkinningMode::kLinear, true, 1);
  Result<PackedDeformData> packed = packDeformAsset(a, 0);
  ASSERT_TRUE(packed.ok());
  Result<CpuDeformKernel> kernel = CpuDeformKernel::create(*packed);
  ASSERT_TRUE(kernel.ok());
  std::vector<gpu::BoneMatrix> bones(a.bone_count);
  std::vector<gpu::ModeBasis> basis(ODESKIN_BASIS_ENTRIES(a.materials.size(), std::size_t{9}));
  std::vector<gpu::Float4> out(10);
  auto expectInvalid = [](const Status& s, const std::string& names) {
    EXPECT_EQ(s.code(), StatusCode::kInvalidArgument) << s.toString();
    EXPECT_NE(s.message().find(names), std::string::npos) << s.message();
  };
  EXPECT_TRUE(kernel->deform(0, bones, basis, out).ok());
  EXPECT_TRUE(kernel->skin(bones, out).ok());
  expectInvalid(kernel->deform(2, bones, basis, out), "segment 2 of 2");
  expectInvalid(kernel->deform(0, std::span(bones).first(1), basis, out), "bones has 1 entries, expected 12");
  expectInvalid(kernel->deform(0, bones, std::span(basis).first(4), out), "basis has 4 entries");
  expectInvalid(kernel->deform(0, bones, basis, std::span(out).first(9)), "out_positions has 9 entries, expected 10");
  expectInvalid(kernel->skin(std::span(bones).first(11), out), "bones has 11 entries");
  expectInvalid(kernel->skin(bones, std::span(out).first(3)), "out_positions has 3 entries");
  // The same inputs are invalid for the fast path.
  EXPECT_EQ((FourierDeformFastJob{&*packed, 2, bones, basis, out, 1}).validate().code(), StatusCode::kInvalidArgument);
}

// The packed layout is float32: an asset with a value beyond 1e38 is refused when packed, where it
// deformed to infinities before.
TEST(CpuDeformKernel, AssetsBeyondFloatRangeAreRefusedWhenPacked) {
  Result<ProceduralArm> arm = makeProceduralArm(ArmOptions{});
  ASSERT_TRUE(arm.ok());
  Result<DeformAsset> fitted = fitDeformAsset(arm->fit_input, FitOptions{});
  ASSERT_TRUE(fitted.ok()) << fitted.status().toString();
  ASSERT_TRUE(packDeformAsset(*fitted).ok());
  auto refused = [](const DeformAsset& a, const std::string& names) {
    const Result<PackedDeformData> packed = packDeformAsset(a);
    ASSERT_FALSE(packed.ok()) << names;
    EXPECT_EQ(packed.status().code(), StatusCode::kInvalidArgument);
    EXPECT_NE(packed.status().message().find(names), std::string::npos) << packed.status().message();
  };
  DeformAsset a = *fitted;
  a.rest_positions[3] *= 1e50;
  refused(a, "deform asset: rest position 3 is outside float32's range");
  a = *fitted;
  a.segments[0].coefficients[5].y = -1e39;
  refused(a, "deform asset: segment 0 coefficient 5 is outside float32's range");
  // A NaN in y or z: std::max over the coordinates dropped it, and the asset played NaN frames.
  for (const int axis : {1, 2}) {
    a = *fitted;
    a.rest_positions[4][axis] = std::nan("");
    refused(a, "deform asset: rest position 4 is outside float32's range");
    a = *fitted;
    a.segments[0].coefficients[6][axis] = std::nan("");
    refused(a, "deform asset: segment 0 coefficient 6 is outside float32's range");
  }
  a = *fitted;
  a.segments[0].base_residuals[2].z = std::numeric_limits<double>::infinity();
  refused(a, "deform asset: segment 0 base residual 2");
}

TEST(CpuDeformKernel, BadPackedDataIsRejectedAtCreate) {
  const PackedDeformData good = testing::randomPackedData(packedOptions());
  ASSERT_TRUE(CpuDeformKernel::create(good).ok());
  auto expectCode = [&](const PackedDeformData& d, StatusCode code, const std::string& names) {
    Result<CpuDeformKernel> k = CpuDeformKernel::create(d);
    ASSERT_FALSE(k.ok()) << names;
    EXPECT_EQ(k.status().code(), code) << k.status().toString();
    EXPECT_NE(k.status().message().find(names), std::string::npos) << k.status().message();
  };
  PackedDeformData d = good;
  d.influence_layout = 3;
  expectCode(d, StatusCode::kInvalidArgument, "influence_layout 3");
  d = good;
  d.skinning = static_cast<SkinningMode>(7);
  expectCode(d, StatusCode::kInvalidArgument, "unknown skinning mode 7");
  d = good;
  d.bindings[4].curve_b = d.curve_count;
  expectCode(d, StatusCode::kInvalidArgument, "binding of vertex 4");
  d = good;
  d.influences[3].bone = d.bone_count;
  d.influences[3].weight = 0.5f;
  expectCode(d, StatusCode::kInvalidArgument, "influenced by bone 7 of 7");
  d = good;
  d.curve_materials[1] = d.material_count;
  expectCode(d, StatusCode::kInvalidArgument, "curve 1 has material");
  d = good;
  d.rest_positions.pop_back();
  expectCode(d, StatusCode::kInvalidArgument, "rest_positions");
  d = good;
  d.coefficients.pop_back();
  expectCode(d, StatusCode::kInvalidArgument, "coefficients");
  d = good;
  for (gpu::SegmentVertex& sv : d.segment_vertices) {
    if (sv.remainder_index != gpu::kNoRemainder) sv.remainder_index += 1000;
  }
  expectCode(d, StatusCode::kInvalidArgument, "out of range");
  d = good;
  d.bindings[2].v = std::numeric_limits<float>::quiet_NaN();
  expectCode(d, StatusCode::kInvalidArgument, "binding of vertex 2 is not finite");
  d = good;
  d.modes = 65;
  expectCode(d, StatusCode::kOutOfRange, "N = 65");
}

}  // namespace
}  // namespace odeskin
