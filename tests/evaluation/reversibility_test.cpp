// SPDX-License-Identifier: MIT
// Thesis Fig. 6.13 analogue: is playing B -> A the mirror of playing A -> B? Two fits of horse
// frames 1 and 5 with one rig (same bind mesh, bones and weights), one with the keys in order
// (A, B), one reversed (B, A); the in-between at tau of the first is compared with the one at
// 1 - tau of the second, with the same skeleton (fitted to the ground-truth frame, or the keys'
// interpolated path).
// - static (gamma = tau, remainders weighted by 3 tau^2 - 2 tau^3, which also satisfies
//   w(1 - tau) = 1 - w(tau)): mirrored up to the fit's key tolerance;
// - dynamic (skin material): not mirrored. Both fits start their segment at rest (a(0) = 0,
//   a'(0) = 0) and arrive with a free rate, so the reversed fit's residual at 1 - tau is
//   r_A + (1 - gamma(1 - tau)) Delta instead of r_A + gamma(tau) Delta (MATH.md 5.2-5.3): the two
//   differ by c(tau) = 1 - gamma(tau) - gamma(1 - tau) times the segment's change, which the test
//   measures against the change itself.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "engine/baselines/baseline_rig.hpp"
#include "engine/baselines/odeskin_baseline.hpp"
#include "engine/io/obj_reader.hpp"
#include "engine/offline/residual_fit.hpp"
#include "engine/offline/time_basis.hpp"
#include "engine/evaluation/evaluation.hpp"
#include "engine/pipeline/fit_pipeline.hpp"
#include "evaluation/pose_difference.hpp"
#include "pipeline/dataset_fixtures.hpp"

namespace odeskin {
namespace {

using testing::Difference;
using testing::difference;
using testing::play;

struct Mirror {
  std::vector<std::vector<Vec3>> frames;  // horse frames 1..5
  DeformAsset forward;                    // keys (frame 1, frame 5)
  DeformAsset reverse;                    // keys (frame 5, frame 1), same rig and bind mesh
  DeformAsset pure_forward, pure_reverse;  // the same without remainders (pure Fourier fits)
  double box = 0.0;
};

// One rig for both directions: the automatic rig of the forward keys, its transforms refitted per
// bone rigidly (as `odeskin evaluate` does), handed to both fits with the bind mesh = frame 1.
Mirror makeMirror() {
  Mirror m;
  for (int f = 1; f <= 5; ++f) {
    Result<ObjMesh> mesh = readObj(testing::horseFrames({f})[0]);
    EXPECT_TRUE(mesh.ok()) << mesh.status().toString();
    if (!mesh.ok()) return m;
    m.frames.push_back(mesh->positions);
  }
  Result<ExampleSet> keys = readObjSequence(testing::horseFrames({1, 5}));
  EXPECT_TRUE(keys.ok()) << keys.status().toString();
  if (!keys.ok()) return m;
  Result<PipelineResult> automatic = runFitPipeline(*keys, PipelineOptions{});
  EXPECT_TRUE(automatic.ok()) << automatic.status().toString();
  if (!automatic.ok()) return m;
  Result<Rig> rig = perBoneRigidRig(automatic->asset, *keys);
  EXPECT_TRUE(rig.ok()) << rig.status().toString();
  if (!rig.ok()) return m;

  ExampleSet forward = *keys;
  forward.rig = std::move(*rig);
  ExampleSet reverse = forward;
  std::reverse(reverse.poses.begin(), reverse.poses.end());
  std::reverse(reverse.pose_labels.begin(), reverse.pose_labels.end());
  std::reverse(reverse.rig->key_poses.begin(), reverse.rig->key_poses.end());
  for (const bool pure : {false, true}) {
    PipelineOptions options;
    options.pure_fourier = pure;
    Result<PipelineResult> f = runFitPipeline(forward, options);
    Result<PipelineResult> r = runFitPipeline(reverse, options);
    EXPECT_TRUE(f.ok() && r.ok());
    if (!(f.ok() && r.ok())) return m;
    (pure ? m.pure_forward : m.forward) = std::move(f->asset);
    (pure ? m.pure_reverse : m.reverse) = std::move(r->asset);
  }
  m.box = longestBoxSide(m.frames[0]);
  return m;
}

struct Pair {
  OdeskinBaseline forward;
  OdeskinBaseline reverse;
};

Pair makePair(const DeformAsset& forward, const DeformAsset& reverse, const Material& material,
              BaselineMethod method) {
  Result<OdeskinBaseline> f = OdeskinBaseline::create(forward, material, method);
  Result<OdeskinBaseline> r = OdeskinBaseline::create(reverse, material, method);
  if (!f.ok() || !r.ok()) throw std::runtime_error("odeskin baseline: " + (f.ok() ? r.status() : f.status()).toString());
  return Pair{std::move(*f), std::move(*r)};
}

class Reversibility : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { mirror_ = new Mirror(makeMirror()); }
  static void TearDownTestSuite() {
    delete mirror_;
    mirror_ = nullptr;
  }
  // The in-between frames 2, 3, 4 (tau = 1/4, 1/2, 3/4) with their skeletons: the truth protocol's
  // (per-bone rigid fit to the frame), or empty for each fit's own key path.
  std::vector<BoneTransform> truthBones(std::size_t frame) const {
    Result<BaselineRig> rig = BaselineRig::fromAsset(mirror_->forward);
    EXPECT_TRUE(rig.ok());
    Result<std::vector<BoneTransform>> bones = rig->fitFrameBones(mirror_->frames[frame], SkeletonFit::kPerBoneRigid);
    EXPECT_TRUE(bones.ok()) << bones.status().toString();
    return bones.ok() ? *bones : std::vector<BoneTransform>{};
  }
  static Mirror* mirror_;
};
Mirror* Reversibility::mirror_ = nullptr;

TEST_F(Reversibility, BothFitsShareOneRig) {
  ASSERT_FALSE(mirror_->forward.rest_positions.empty());
  EXPECT_EQ(mirror_->forward.rest_positions, mirror_->reverse.rest_positions);
  EXPECT_EQ(mirror_->forward.bone_pivots, mirror_->reverse.bone_pivots);
  EXPECT_EQ(mirror_->forward.influences.weights, mirror_->reverse.influences.weights);
  EXPECT_EQ(mirror_->forward.curveCount(), mirror_->reverse.curveCount());
}

TEST_F(Reversibility, StaticPlaysBackwardsAsItsMirror) {
  ASSERT_FALSE(mirror_->forward.rest_positions.empty());
  Pair p = makePair(mirror_->forward, mirror_->reverse, staticMaterial(), BaselineMethod::kOdeskinStatic);
  double worst_truth = 0.0, worst_keys = 0.0;
  for (std::size_t frame = 1; frame <= 3; ++frame) {
    const double tau = 0.25 * static_cast<double>(frame);
    const std::vector<BoneTransform> bones = truthBones(frame);
    const Difference truth = difference(play(p.forward, 0, tau, bones), play(p.reverse, 0, 1.0 - tau, bones), mirror_->box);
    const Difference keys = difference(play(p.forward, 0, tau, {}), play(p.reverse, 0, 1.0 - tau, {}), mirror_->box);
    std::printf("[ measured ] static, tau %.2f: |A->B(tau) - B->A(1 - tau)| max %.2e (truth skeleton), %.2e (key "
                "path) of the box\n",
                tau, truth.max, keys.max);
    worst_truth = std::max(worst_truth, truth.max);
    worst_keys = std::max(worst_keys, keys.max);
  }
  // The fits are linear in the residuals, and gamma and the remainder weight are symmetric
  // (gamma(1 - tau) = 1 - gamma(tau)): where a vertex has a remainder in both fits the mirror is
  // exact, elsewhere it differs by the series' error there, which the key tolerance (1e-4 of the
  // box, PipelineOptions) bounds.
  EXPECT_LT(worst_truth, 1e-4);
  EXPECT_LT(worst_keys, 1e-4);
}

TEST_F(Reversibility, DynamicIsNotMirrored) {
  ASSERT_FALSE(mirror_->forward.rest_positions.empty());
  Pair dynamic = makePair(mirror_->forward, mirror_->reverse, skinMaterial(), BaselineMethod::kOdeskinDynamic);
  Pair still = makePair(mirror_->forward, mirror_->reverse, staticMaterial(), BaselineMethod::kOdeskinStatic);
  Result<ModeTimeBasis> basis = ModeTimeBasis::create(skinMaterial(), 1);
  ASSERT_TRUE(basis.ok());
  for (std::size_t frame = 1; frame <= 3; ++frame) {
    const double tau = 0.25 * static_cast<double>(frame);
    const std::vector<BoneTransform> bones = truthBones(frame);
    const Difference mirror =
        difference(play(dynamic.forward, 0, tau, bones), play(dynamic.reverse, 0, 1.0 - tau, bones), mirror_->box);
    // The static variant's motion over the whole segment with the same skeleton: the scale of the
    // asymmetry.
    const Difference change = difference(play(still.forward, 0, 1.0, bones), play(still.forward, 0, 0.0, bones), mirror_->box);
    const double c = 1.0 - basis->at(tau).gamma - basis->at(1.0 - tau).gamma;
    std::printf("[ measured ] dynamic, tau %.2f: |A->B(tau) - B->A(1 - tau)| max %.3f %%, mean %.3f %% of the box; "
                "the segment's change max %.3f %%, mean %.3f %%; c(tau) = 1 - gamma(tau) - gamma(1 - tau) = %.3f\n",
                tau, 100 * mirror.max, 100 * mirror.mean, 100 * change.max, 100 * change.mean, c);
    EXPECT_GT(mirror.mean, 0.1 * c * change.mean) << tau;
    EXPECT_LT(mirror.max, change.max) << tau;
  }
}

// Without remainders (pure Fourier fits, series S of the change Delta = S + E) both variants'
// asymmetries can be written down: the static one is E (the series' own error, the same at every
// tau), the dynamic one E + c(tau) S. So vertex by vertex, dynamic asymmetry - static asymmetry =
// c(tau) (A->B(1) - A->B(0)) of the static forward fit (= S, skinned linearly by LBS).
TEST_F(Reversibility, DynamicAsymmetryIsTheLagOfBothEnds) {
  ASSERT_FALSE(mirror_->pure_forward.rest_positions.empty());
  Pair dynamic =
      makePair(mirror_->pure_forward, mirror_->pure_reverse, skinMaterial(), BaselineMethod::kOdeskinDynamic);
  Pair still = makePair(mirror_->pure_forward, mirror_->pure_reverse, staticMaterial(), BaselineMethod::kOdeskinStatic);
  Result<ModeTimeBasis> basis = ModeTimeBasis::create(skinMaterial(), 1);
  ASSERT_TRUE(basis.ok());
  for (std::size_t frame = 1; frame <= 3; ++frame) {
    const double tau = 0.25 * static_cast<double>(frame);
    const std::vector<BoneTransform> bones = truthBones(frame);
    const double c = 1.0 - basis->at(tau).gamma - basis->at(1.0 - tau).gamma;
    const std::vector<Vec3> dynamic_forward = play(dynamic.forward, 0, tau, bones);
    const std::vector<Vec3> dynamic_reverse = play(dynamic.reverse, 0, 1.0 - tau, bones);
    const std::vector<Vec3> static_forward = play(still.forward, 0, tau, bones);
    const std::vector<Vec3> static_reverse = play(still.reverse, 0, 1.0 - tau, bones);
    const std::vector<Vec3> end = play(still.forward, 0, 1.0, bones);
    const std::vector<Vec3> start = play(still.forward, 0, 0.0, bones);
    double worst = 0.0, series_error = 0.0;
    for (std::size_t i = 0; i < end.size(); ++i) {
      const Vec3 dynamic_asymmetry = dynamic_reverse[i] - dynamic_forward[i];
      const Vec3 static_asymmetry = static_reverse[i] - static_forward[i];
      const Vec3 off = dynamic_asymmetry - static_asymmetry - c * (end[i] - start[i]);
      worst = std::max(worst, glm::length(off) / mirror_->box);
      series_error = std::max(series_error, glm::length(static_asymmetry) / mirror_->box);
    }
    std::printf("[ measured ] pure Fourier, tau %.2f: static asymmetry (the series error E) max %.2e; "
                "dynamic - static asymmetry - c(tau) S: max %.2e of the box, c = %.4f\n",
                tau, series_error, worst, c);
    EXPECT_LT(worst, 1e-9) << tau;
  }
}

}  // namespace
}  // namespace odeskin
