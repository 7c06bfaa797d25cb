// SPDX-License-Identifier: MIT
#include "engine/offline/residual_fit.hpp"

#include <limits>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "engine/offline/deform_player.hpp"
#include "engine/offline/procedural_arm.hpp"

namespace odeskin {
namespace {

std::vector<Vec3> play(const DeformAsset& asset, const DeformPlayer& player, double t) {
  const auto [segment, tau] = player.locate(t);
  std::vector<Vec3> out(asset.vertexCount());
  EXPECT_TRUE(player.play(asset, segment, tau, out).ok());
  return out;
}

double maxDistance(std::span<const Vec3> a, std::span<const Vec3> b) {
  double worst = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) worst = std::max(worst, glm::length(a[i] - b[i]));
  return worst;
}

TEST(ProceduralArm, CountsAndCurves) {
  ArmOptions o;
  Result<ProceduralArm> arm = makeProceduralArm(o);
  ASSERT_TRUE(arm.ok());
  const FitInput& in = arm->fit_input;
  EXPECT_EQ(in.rest_positions.size(), armVertexCount(o));
  EXPECT_EQ(in.faces.faceCount(), (o.rings - 1) * o.ring_vertices);
  EXPECT_EQ(in.curves.size(), 21u);  // rings 0, 2, ..., 40
  EXPECT_TRUE(validateInfluences(in.influences, in.rest_positions.size(), 2).ok());
  // The elbow does not move: the forearm turns about it.
  EXPECT_LT(glm::length(in.key_poses[1][1].apply(in.bone_pivots[1]) - in.bone_pivots[1]), 1e-15);
}

TEST(ProceduralArm, RejectsBadOptions) {
  ArmOptions o;
  o.rings = 2;
  EXPECT_EQ(makeProceduralArm(o).status().code(), StatusCode::kInvalidArgument);
  o = ArmOptions{};
  o.radius = std::nan("");
  EXPECT_EQ(makeProceduralArm(o).status().code(), StatusCode::kInvalidArgument);
  o = ArmOptions{};
  o.curve_stride = 0;
  EXPECT_EQ(makeProceduralArm(o).status().code(), StatusCode::kInvalidArgument);
}

TEST(ResidualFit, BindSpaceCorrectiveIsTheBulge) {
  // The arm's end pose is LBS(X + bulge), so the exact bind-space corrective of key 1 is the bulge:
  // rotation-aware (bind space) residuals do not depend on how far the elbow bends.
  ArmOptions bent;
  ArmOptions straight;
  straight.bend_degrees = 0.0;
  Result<ProceduralArm> a = makeProceduralArm(bent);
  Result<ProceduralArm> b = makeProceduralArm(straight);
  ASSERT_TRUE(a.ok() && b.ok());
  FitOptions opt;
  Result<DeformAsset> fa = fitDeformAsset(a->fit_input, opt);
  Result<DeformAsset> fb = fitDeformAsset(b->fit_input, opt);
  ASSERT_TRUE(fa.ok()) << fa.status().toString();
  ASSERT_TRUE(fb.ok());
  const auto& ca = fa->segments[0].coefficients;
  const auto& cb = fb->segments[0].coefficients;
  for (std::size_t k = 0; k < ca.size(); ++k) ASSERT_LT(glm::length(ca[k] - cb[k]), 1e-12) << k;
}

TEST(ResidualFit, KeysAreHitWithinTolerance) {
  Result<ProceduralArm> arm = makeProceduralArm(ArmOptions{});
  ASSERT_TRUE(arm.ok());
  FitOptions opt;
  opt.key_tolerance = 1e-6;
  opt.materials = {skinMaterial()};
  FitReport report;
  Result<DeformAsset> asset = fitDeformAsset(arm->fit_input, opt, &report);
  ASSERT_TRUE(asset.ok()) << asset.status().toString();
  ASSERT_EQ(report.key_error.size(), 2u);
  EXPECT_LE(report.key_error[0], 1e-6);
  EXPECT_LE(report.key_error[1], 1e-6);
  Result<DeformPlayer> player = DeformPlayer::create(*asset);
  ASSERT_TRUE(player.ok());
  const double box = longestBoxSide(arm->end_positions);
  EXPECT_LE(maxDistance(play(*asset, *player, 0.0), arm->start_positions), 1e-12);
  EXPECT_LE(maxDistance(play(*asset, *player, 1.0), arm->end_positions), 1e-6 * box);
}

TEST(ResidualFit, PureFourierReportsItsKeyError) {
  Result<ProceduralArm> arm = makeProceduralArm(ArmOptions{});
  ASSERT_TRUE(arm.ok());
  FitOptions opt;
  opt.modes = 2;
  opt.pure_fourier = true;
  FitReport report;
  ASSERT_TRUE(fitDeformAsset(arm->fit_input, opt, &report).ok());
  EXPECT_EQ(report.remainder_count, 0u);
  EXPECT_GT(report.key_error[1], 1e-4);  // N = 2 cannot draw the one-sided bulge
  EXPECT_NEAR(report.key_error[1], report.max_series_error, 0.5 * report.max_series_error);
  // More modes, smaller series error.
  opt.modes = 9;
  FitReport finer;
  ASSERT_TRUE(fitDeformAsset(arm->fit_input, opt, &finer).ok());
  EXPECT_LT(finer.max_series_error, report.max_series_error);
}

TEST(ResidualFit, AKeyBeyondDoublePrecisionIsAnErrorNotAnAsset) {
  // A bone moved 1e20 away in the second key: its residual (the pose minus LBS) is ~1e20, whose
  // last digits are ~1e4, far coarser than the arm. No asset can hit that key.
  Result<ProceduralArm> arm = makeProceduralArm(ArmOptions{});
  ASSERT_TRUE(arm.ok());
  FitInput in = arm->fit_input;
  in.key_poses[1][1].translation.x += 1e20;
  for (const bool pure : {false, true}) {
    FitOptions opt;
    opt.pure_fourier = pure;
    const Result<DeformAsset> asset = fitDeformAsset(in, opt);
    if (pure) {
      ASSERT_TRUE(asset.ok()) << asset.status().toString();  // its key error is only reported
      continue;
    }
    ASSERT_FALSE(asset.ok());
    EXPECT_EQ(asset.status().code(), StatusCode::kOutOfRange);
    EXPECT_NE(asset.status().message().find("misses example pose 1 by "), std::string::npos) << asset.status().message();
  }
}

TEST(ResidualFit, StaticMaterialIsLinearInTime) {
  // rho = eta = 0 gives gamma_n(tau) = tau: the bind-space residual grows linearly (PIPELINE.md 7).
  ArmOptions o;
  o.bend_degrees = 0.0;
  Result<ProceduralArm> arm = makeProceduralArm(o);
  ASSERT_TRUE(arm.ok());
  Result<DeformAsset> asset = fitDeformAsset(arm->fit_input, FitOptions{});
  ASSERT_TRUE(asset.ok());
  Result<DeformPlayer> player = DeformPlayer::create(*asset);
  ASSERT_TRUE(player.ok());
  const std::vector<Vec3> mid = play(*asset, *player, 0.3);
  // Exact up to the series error left below half the key tolerance, times tau. Remainders follow
  // remainderWeight(tau) instead of tau (bones are the identity here, so bind space is posed space).
  const double bound = 0.3 * 0.5 * FitOptions{}.key_tolerance * longestBoxSide(arm->end_positions) + 1e-14;
  const DeformSegment& seg = asset->segments[0];
  for (std::size_t i = 0; i < mid.size(); ++i) {
    Vec3 expected = 0.7 * arm->start_positions[i] + 0.3 * arm->end_positions[i];
    if (seg.remainder_indices[i] != kNoRemainder) {
      expected += (remainderWeight(0.3) - 0.3) * seg.remainders[seg.remainder_indices[i]];
    }
    ASSERT_LT(glm::length(mid[i] - expected), bound) << i;
  }
}

TEST(ResidualFit, RateIsContinuousAcrossKeys) {
  // Three keys: bend 0 -> 60 -> 120 degrees with growing bulge. With a dynamic material the
  // deformation's velocity at the end of segment 0 must equal its velocity at the start of
  // segment 1 (MATH.md 5.2, erratum G7); without the rate basis it would restart at zero.
  ArmOptions o;
  o.bend_degrees = 60.0;
  o.bulge = 0.2;
  Result<ProceduralArm> first = makeProceduralArm(o);
  o.bend_degrees = 120.0;
  o.bulge = 0.4;
  Result<ProceduralArm> second = makeProceduralArm(o);
  ASSERT_TRUE(first.ok() && second.ok());
  FitInput in = first->fit_input;
  in.poses.push_back(second->end_positions);
  in.key_poses.push_back(second->fit_input.key_poses[1]);
  FitOptions opt;
  opt.materials = {Material{1.0, 0.5, 30.0, 0.01}};
  // Sparse remainders follow gamma_0 without a rate of their own; leave them out to test the
  // Fourier rate chain alone. The key then carries the series error as a position step.
  opt.pure_fourier = true;
  FitReport report;
  Result<DeformAsset> asset = fitDeformAsset(in, opt, &report);
  ASSERT_TRUE(asset.ok()) << asset.status().toString();
  Result<DeformPlayer> player = DeformPlayer::create(*asset);
  ASSERT_TRUE(player.ok());
  // Velocity of the bind-space residual D by one-sided differences on each side of the join.
  const double h = 1e-5;
  auto residual = [&](std::uint32_t segment, double tau) {
    std::vector<ModeBasisValue> basis(player->basisSize());
    player->basisAt(tau, basis);
    std::vector<BoneTransform> identity(asset->bone_count, BoneTransform(1.0));
    std::vector<Vec3> out(asset->vertexCount());
    EXPECT_TRUE(referenceJob(*asset, segment, basis, identity, out).run().ok());
    return out;
  };
  const auto before0 = residual(0, 1.0 - h), before1 = residual(0, 1.0);
  const auto after0 = residual(1, 0.0), after1 = residual(1, h);
  double worst_jump = 0.0, typical = 0.0;
  for (std::size_t i = 0; i < before0.size(); ++i) {
    const Vec3 v_before = (before1[i] - before0[i]) / h;
    const Vec3 v_after = (after1[i] - after0[i]) / h;
    worst_jump = std::max(worst_jump, glm::length(v_after - v_before));
    typical = std::max(typical, glm::length(v_before));
    ASSERT_LT(glm::length(before1[i] - after0[i]), 1.01 * report.max_series_error * longestBoxSide(in.poses[1]))
        << "position step at the key exceeds the series error, vertex " << i;
  }
  EXPECT_GT(typical, 1e-3);
  EXPECT_LT(worst_jump, 1e-3 * typical + 1e-6);
}

TEST(ResidualFit, CurvesWithFewPointsUseFewerModes) {
  Result<ProceduralArm> arm = makeProceduralArm(ArmOptions{});
  ASSERT_TRUE(arm.ok());
  FitOptions opt;
  opt.modes = 16;  // rings of 32 vertices determine at most 15 modes: every curve drops to 15
  FitReport report;
  Result<DeformAsset> asset = fitDeformAsset(arm->fit_input, opt, &report);
  ASSERT_TRUE(asset.ok()) << asset.status().toString();
  EXPECT_EQ(report.reduced_curves, arm->fit_input.curves.size());
  for (double e : report.key_error) EXPECT_LT(e, opt.key_tolerance);
  // A 3-point curve keeps only its mean.
  FitInput in = arm->fit_input;
  in.curves[0].points.resize(3);
  in.curves[0].v.resize(3);
  ASSERT_TRUE(fitDeformAsset(in, FitOptions{}, &report).ok());
  EXPECT_EQ(report.reduced_curves, 1u);
  for (double e : report.key_error) EXPECT_LT(e, 1e-4);
}

TEST(ResidualFit, NearlyOpposedBlendsAreReboundToTheirDominantBone) {
  // At a 170 degree elbow, LBS's blend of the two bones at equal weights shrinks to cos(85 deg) =
  // 0.09 across the bend: A^-1 would blow the corrective up elevenfold.
  ArmOptions o;
  o.bend_degrees = 170.0;
  Result<ProceduralArm> arm = makeProceduralArm(o);
  ASSERT_TRUE(arm.ok());
  FitReport report;
  Result<DeformAsset> asset = fitDeformAsset(arm->fit_input, FitOptions{}, &report);
  ASSERT_TRUE(asset.ok()) << asset.status().toString();
  EXPECT_GT(report.ill_conditioned, 0u);
  std::size_t rigid = 0;
  for (std::size_t i = 0; i < asset->vertexCount(); ++i) {
    const std::uint32_t count = asset->influences.offsets[i + 1] - asset->influences.offsets[i];
    const std::uint32_t before = arm->fit_input.influences.offsets[i + 1] - arm->fit_input.influences.offsets[i];
    if (count == 1 && before > 1) ++rigid;
  }
  EXPECT_EQ(rigid, report.ill_conditioned);
  for (double e : report.key_error) EXPECT_LT(e, 1e-4);
  // The same arm at 100 degrees keeps every blend.
  ASSERT_TRUE(fitDeformAsset(makeProceduralArm(ArmOptions{})->fit_input, FitOptions{}, &report).ok());
  EXPECT_EQ(report.ill_conditioned, 0u);
}

// The status is kInvalidArgument and its message holds `expected`.
void expectRejected(const Result<DeformAsset>& result, const std::string& expected) {
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(result.status().message().find(expected), std::string::npos) << result.status().message();
}

TEST(ResidualFit, RejectsMismatchedInput) {
  Result<ProceduralArm> arm = makeProceduralArm(ArmOptions{});
  ASSERT_TRUE(arm.ok());
  FitInput in = arm->fit_input;
  in.poses[1].pop_back();
  EXPECT_EQ(fitDeformAsset(in, FitOptions{}).status().code(), StatusCode::kInvalidArgument);
  in = arm->fit_input;
  in.poses[1][5].y = std::nan("");
  expectRejected(fitDeformAsset(in, FitOptions{}), "fit: pose 1: vertex 5 is not finite");
  in = arm->fit_input;
  in.rest_positions[7].x = std::numeric_limits<double>::infinity();
  expectRejected(fitDeformAsset(in, FitOptions{}), "fit: the bind mesh: vertex 7 is not finite");
  in = arm->fit_input;
  for (Vec3& p : in.poses[0]) p *= 1e200;  // finite, but its squared lengths overflow
  expectRejected(fitDeformAsset(in, FitOptions{}), "fit: pose 0: the mesh is too large");
  in = arm->fit_input;
  in.poses.pop_back();
  in.key_poses.pop_back();
  EXPECT_EQ(fitDeformAsset(in, FitOptions{}).status().code(), StatusCode::kInvalidArgument);
  in = arm->fit_input;
  in.curves[0].points.push_back(in.curves[1].points[0]);  // without its v
  EXPECT_EQ(fitDeformAsset(in, FitOptions{}).status().code(), StatusCode::kInvalidArgument);
  FitOptions too_many;
  too_many.modes = 16;  // rings of 32 vertices determine at most 15 modes (2N+1 <= 32)
  too_many.adaptive_modes = false;
  Result<DeformAsset> rank = fitDeformAsset(arm->fit_input, too_many);
  EXPECT_EQ(rank.status().code(), StatusCode::kIllPosed);
  EXPECT_NE(rank.status().message().find("curve 0"), std::string::npos) << rank.status().message();
  FitOptions resonant;
  resonant.materials = {Material{1.0, -10.0, 46.95719084373242, 0.0}};
  EXPECT_EQ(fitDeformAsset(arm->fit_input, resonant).status().code(), StatusCode::kIllPosed);
}

// Four keys (rest, bent 100 degrees, bent 50, rest) of the arm: three segments, rates carried.
FitInput fourKeyArm() {
  ArmOptions half;
  half.bend_degrees = 50.0;
  Result<ProceduralArm> full = makeProceduralArm(ArmOptions{});
  Result<ProceduralArm> partial = makeProceduralArm(half);
  EXPECT_TRUE(full.ok() && partial.ok());
  FitInput in = full->fit_input;
  in.poses = {full->start_positions, full->end_positions, partial->end_positions, full->start_positions};
  in.key_poses = {full->fit_input.key_poses[0], full->fit_input.key_poses[1], partial->fit_input.key_poses[1],
                  full->fit_input.key_poses[0]};
  return in;
}

TEST(ResidualFit, KeyErrorsAreTheReferenceKernelsToTheBit) {
  // The fit plays its keys back with the reference kernel's arithmetic, each vertex's harmonics
  // computed once for its curves and both frames of a key: the same numbers as playing every
  // frame with FourierDeformJob (DeformPlayer::play).
  const FitInput in = fourKeyArm();
  for (const SkinningMode skinning : {SkinningMode::kLinear, SkinningMode::kDualQuaternion}) {
    for (const ResidualSpace space : {ResidualSpace::kBind, ResidualSpace::kPosed}) {
      for (const bool pure : {false, true}) {
        FitOptions opt;
        opt.skinning = skinning;
        opt.residual_space = space;
        opt.pure_fourier = pure;
        opt.modes = 5;
        opt.materials = {skinMaterial(), Material{1.0, 4.0, 30.0, 0.0}};
        opt.curve_materials.assign(in.curves.size(), 0);
        for (std::size_t c = 0; c < in.curves.size(); c += 3) opt.curve_materials[c] = 1;
        FitReport report;
        Result<DeformAsset> asset = fitDeformAsset(in, opt, &report);
        ASSERT_TRUE(asset.ok()) << asset.status().toString();
        asset->skinning = skinning;
        Result<DeformPlayer> player = DeformPlayer::create(*asset);
        ASSERT_TRUE(player.ok());
        ASSERT_EQ(report.key_error.size(), 4u);
        bool rates = false;
        for (const Vec3& r : asset->segments[2].rates) rates = rates || glm::length(r) > 0.0;
        EXPECT_TRUE(rates);
        std::vector<Vec3> out(asset->vertexCount());
        for (std::size_t k = 0; k < 4; ++k) {
          double worst = 0.0;
          for (int side = 0; side < 2; ++side) {
            if ((side == 0 && k == 3) || (side == 1 && k == 0)) continue;
            const auto segment = static_cast<std::uint32_t>(side == 0 ? k : k - 1);
            ASSERT_TRUE(player->play(*asset, segment, side == 0 ? 0.0 : 1.0, out).ok());
            worst = std::max(worst, maxDistance(out, in.poses[k]));
          }
          EXPECT_EQ(report.key_error[k], worst / longestBoxSide(in.poses[k]))
              << "key " << k << ", skinning " << static_cast<int>(skinning) << ", space " << static_cast<int>(space);
        }
      }
    }
  }
}

}  // namespace
}  // namespace odeskin
