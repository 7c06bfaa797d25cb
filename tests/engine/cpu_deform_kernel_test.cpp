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
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "engine/kernels/fourier_deform_fast_job.hpp"
#include "engine/kernels/lbs_job.hpp"
#include "engine/offline/deform_player.hpp"
#include "engine/offline/procedural_arm.hpp"
#include "engine/offline/residual_fit.hpp"
#include "engine/test_meshes.hpp"

namespace odeskin {
namespace {

constexpr double kRelativeTolerance = 1e-5;

// Synthetic packed data in the GPU layout (no fit): random curve pairs in either order, w anywhere
// in [0, 1] (0 and 1 included), 1 to 6 influences per vertex, sparse remainders on a third of the
// vertices, and affine bones near the identity.
struct PackedOptions {
  std::uint32_t vertex_count = 100;
  std::uint32_t influence_layout = ODESKIN_INFLUENCES_SPARSE;
  ResidualSpace residual_space = ResidualSpace::kBind;
  SkinningMode skinning = SkinningMode::kLinear;
  bool rates = true;
  std::uint32_t seed = 1;
};

PackedDeformData randomPacked(const PackedOptions& o) {
  std::mt19937 rng(o.seed);
  auto uniform = [&](float lo, float hi) { return std::uniform_real_distribution<float>(lo, hi)(rng); };
  auto below = [&](std::uint32_t n) { return std::uniform_int_distribution<std::uint32_t>(0, n - 1)(rng); };
  PackedDeformData d;
  d.vertex_count = o.vertex_count;
  d.modes = 9;
  d.curve_count = 23;
  d.material_count = 2;
  d.bone_count = 7;
  d.segment_count = 3;
  d.influence_layout = o.influence_layout;
  d.residual_space = o.residual_space;
  d.skinning = o.skinning;
  for (std::uint32_t i = 0; i < d.vertex_count; ++i) {
    d.rest_positions.push_back({uniform(-1, 1), uniform(-1, 1), uniform(-1, 1), 0.0f});
    const std::uint32_t pick = below(8);
    const float w = pick == 0 ? 0.0f : (pick == 1 ? 1.0f : uniform(0, 1));
    d.bindings.push_back({below(d.curve_count), below(d.curve_count), w, uniform(0, 0.999f)});
  }
  for (std::uint32_t s = 0; s < d.segment_count; ++s) {
    d.remainder_base.push_back(static_cast<std::uint32_t>(d.remainders.size()));
    std::uint32_t local = 0;
    for (std::uint32_t i = 0; i < d.vertex_count; ++i) {
      gpu::SegmentVertex sv{uniform(-0.05f, 0.05f), uniform(-0.05f, 0.05f), uniform(-0.05f, 0.05f), gpu::kNoRemainder};
      if (s != 1 && below(3) == 0) {  // segment 1 has no remainder at all
        sv.remainder_index = local++;
        d.remainders.push_back({uniform(-0.02f, 0.02f), uniform(-0.02f, 0.02f), uniform(-0.02f, 0.02f), 0.0f});
      }
      d.segment_vertices.push_back(sv);
    }
  }
  for (std::uint32_t c = 0; c < d.curve_count; ++c) d.curve_materials.push_back(below(d.material_count));
  const std::uint32_t m_count = d.coefficientsPerCurve();
  for (std::uint32_t k = 0; k < d.segment_count * d.curve_count * m_count; ++k) {
    const std::uint32_t m = k % m_count;
    const bool zero = (k / m_count) % 3 == 0 && m > 4 && m + 1 < m_count;  // every third curve stops at n = 2
    const float scale = zero ? 0.0f : 0.1f;
    d.coefficients.push_back({scale * uniform(-1, 1), scale * uniform(-1, 1), scale * uniform(-1, 1), 0.0f});
    if (o.rates) d.rates.push_back({scale * uniform(-1, 1), scale * uniform(-1, 1), scale * uniform(-1, 1), 0.0f});
  }
  const std::uint32_t max_influences = o.influence_layout == 0 ? 6 : std::min<std::uint32_t>(6, o.influence_layout);
  if (o.influence_layout == ODESKIN_INFLUENCES_SPARSE) d.influence_offsets.push_back(0);
  for (std::uint32_t i = 0; i < d.vertex_count; ++i) {
    const std::uint32_t count = 1 + below(max_influences);
    std::vector<gpu::Influence> row;
    float sum = 0.0f;
    for (std::uint32_t k = 0; k < count; ++k) {
      row.push_back({below(d.bone_count), uniform(0.05f, 1.0f)});  // repeated bones allowed
      sum += row.back().weight;
    }
    for (gpu::Influence& inf : row) inf.weight /= sum;
    if (o.influence_layout != ODESKIN_INFLUENCES_SPARSE) row.resize(o.influence_layout, gpu::Influence{0, 0.0f});
    d.influences.insert(d.influences.end(), row.begin(), row.end());
    if (o.influence_layout == ODESKIN_INFLUENCES_SPARSE) {
      d.influence_offsets.push_back(static_cast<std::uint32_t>(d.influences.size()));
    }
  }
  return d;
}

std::vector<gpu::BoneMatrix> randomAffineBones(std::uint32_t count, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-0.3f, 0.3f);
  std::vector<gpu::BoneMatrix> bones;
  for (std::uint32_t b = 0; b < count; ++b) {
    bones.push_back({{1 + u(rng), u(rng), u(rng), u(rng)}, {u(rng), 1 + u(rng), u(rng), u(rng)},
                     {u(rng), u(rng), 1 + u(rng), u(rng)}});
  }
  return bones;
}

std::vector<gpu::ModeBasis> randomGpuBasis(std::size_t count, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<gpu::ModeBasis> basis;
  for (std::size_t k = 0; k < count; ++k) basis.push_back({u(rng), u(rng)});
  return basis;
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
    EXPECT_EQ(0, std::memcmp(one.data(), two.data(), one.size() * sizeof(gpu::Float4))) << what << " threads";
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
        PackedOptions o;
        o.vertex_count = 537;
        o.influence_layout = layout;
        o.residual_space = layout == 4 ? ResidualSpace::kPosed : ResidualSpace::kBind;
        o.rates = rates;
        o.skinning = skinning;
        o.seed = 11 + layout;
        const PackedDeformData d = randomPacked(o);
        const std::vector<gpu::BoneMatrix> bones = randomAffineBones(d.bone_count, 2);
        const std::vector<gpu::ModeBasis> basis = randomGpuBasis(ODESKIN_BASIS_ENTRIES(d.material_count, d.modes), 3);
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
      EXPECT_EQ(0, std::memcmp(out.data(), two.data(), out.size() * sizeof(gpu::Float4)));
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
  EXPECT_EQ(0, std::memcmp(inside.data(), given.data(), inside.size() * sizeof(gpu::Float4)));
  ASSERT_TRUE(kernel->skin(f.gpu_bones, inside).ok());
  ASSERT_TRUE(kernel->skin(f.gpu_bones, dual_quats, given).ok());
  EXPECT_EQ(0, std::memcmp(inside.data(), given.data(), inside.size() * sizeof(gpu::Float4)));
  EXPECT_EQ(kernel->deform(1, f.gpu_bones, std::span(dual_quats).first(3), f.gpu_basis, given).code(),
            StatusCode::kInvalidArgument);
}

// A vertex without weight has no dual-quaternion blend: it takes the LBS result (the origin), as
// the fast path does, and its neighbours in the block are unaffected.
TEST_P(CpuDeformKernelArchs, DegenerateDualQuaternionBlendFallsBackToLbs) {
  PackedOptions o;
  o.vertex_count = 40;
  o.influence_layout = 4;
  o.skinning = SkinningMode::kDualQuaternion;
  PackedDeformData d = randomPacked(o);
  for (std::uint32_t k = 0; k < 4; ++k) d.influences[5 * 4 + k].weight = 0.0f;
  const std::vector<gpu::BoneMatrix> bones = randomAffineBones(d.bone_count, 2);
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
  const PackedDeformData d = randomPacked({});
  Result<CpuDeformKernel> kernel = CpuDeformKernel::create(d);
  ASSERT_TRUE(kernel.ok());
  if (std::getenv("ODESKIN_CPU_KERNEL_ARCH") == nullptr) {
    EXPECT_EQ(kernel->arch(), supportedCpuKernelArchs().front());
  }
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

TEST(CpuDeformKernel, BadPackedDataIsRejectedAtCreate) {
  const PackedDeformData good = randomPacked({});
  ASSERT_TRUE(CpuDeformKernel::create(good).ok());
  auto expectCode = [&](PackedDeformData d, StatusCode code, const std::string& names) {
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
