// SPDX-License-Identifier: MIT
// Acceptance of the fitting pipeline on real mesh sequences (issue 3, point 7): the played
// animation reproduces every example pose at its key time within 1e-4 of the bounding box, every
// vertex is bound to the curves, and the motion is C1 across segment joins.
#include "engine/pipeline/fit_pipeline.hpp"

#include <gtest/gtest.h>

#include "dataset_fixtures.hpp"
#include "engine/io/obj_reader.hpp"
#include "engine/offline/deform_player.hpp"

namespace odeskin {
namespace {

using testing::catPoses;
using testing::horseFrames;

std::vector<Vec3> play(const DeformAsset& asset, const DeformPlayer& player, std::uint32_t segment, double tau) {
  std::vector<Vec3> out(asset.vertexCount());
  EXPECT_TRUE(player.play(asset, segment, tau, out).ok());
  return out;
}

// Plays every key back independently of the fit's own report and checks it against the input.
void expectKeysReproduced(const ExampleSet& ex, const PipelineResult& result, double tolerance) {
  Result<DeformPlayer> player = DeformPlayer::create(result.asset);
  ASSERT_TRUE(player.ok()) << player.status().toString();
  const std::size_t keys = ex.poses.size();
  for (std::size_t k = 0; k < keys; ++k) {
    const auto [segment, tau] = player->locate(static_cast<double>(k));
    const std::vector<Vec3> played = play(result.asset, *player, segment, tau);
    double worst = 0.0;
    for (std::size_t i = 0; i < played.size(); ++i) worst = std::max(worst, glm::length(played[i] - ex.poses[k][i]));
    const double box = longestBoxSide(ex.poses[k]);
    EXPECT_LT(worst / box, tolerance) << ex.pose_labels[k];
    EXPECT_LT(result.report.key_error[k], tolerance) << ex.pose_labels[k];
  }
}

// Velocity of every vertex from one-sided differences on both sides of each join.
void expectC1AcrossJoins(const PipelineResult& result) {
  Result<DeformPlayer> player = DeformPlayer::create(result.asset);
  ASSERT_TRUE(player.ok());
  const double h = 1e-5;
  for (std::uint32_t s = 1; s < player->segmentCount(); ++s) {
    const auto b0 = play(result.asset, *player, s - 1, 1.0 - h), b1 = play(result.asset, *player, s - 1, 1.0);
    const auto a0 = play(result.asset, *player, s, 0.0), a1 = play(result.asset, *player, s, h);
    double worst_jump = 0.0, fastest = 0.0;
    for (std::size_t i = 0; i < b0.size(); ++i) {
      const Vec3 before = (b1[i] - b0[i]) / h;
      const Vec3 after = (a1[i] - a0[i]) / h;
      worst_jump = std::max(worst_jump, glm::length(after - before));
      fastest = std::max(fastest, glm::length(before));
    }
    EXPECT_LT(worst_jump, 1e-3 * fastest) << "velocity jumps at key " << s;
  }
}

PipelineResult fitOrFail(const ExampleSet& ex, const PipelineOptions& options) {
  Result<PipelineResult> result = runFitPipeline(ex, options);
  EXPECT_TRUE(result.ok()) << result.status().toString();
  return result.ok() ? std::move(*result) : PipelineResult{};
}

TEST(FitPipeline, CylinderWithItsGroundTruthRig) {
  Result<ExampleSet> ex = testing::cylinderWithRig(true, true);
  ASSERT_TRUE(ex.ok()) << ex.status().toString();
  const PipelineResult result = fitOrFail(*ex, PipelineOptions{});
  ASSERT_EQ(result.asset.segments.size(), 3u);
  expectKeysReproduced(*ex, result, 1e-4);
  expectC1AcrossJoins(result);
}

// A given rig says how far it skins from the poses; transforms of another take (poses-1's .Tmat
// files for poses-2's meshes) still fit, the residual carrying the difference, but are warned of.
TEST(FitPipeline, AGivenRigFarFromThePosesIsWarnedOf) {
  Result<ExampleSet> ex = testing::cylinderWithRig(true, true);
  ASSERT_TRUE(ex.ok()) << ex.status().toString();
  const PipelineResult matched = fitOrFail(*ex, PipelineOptions{});
  EXPECT_NE(matched.rig_summary.find("given transforms (LBS error mean "), std::string::npos) << matched.rig_summary;
  EXPECT_TRUE(matched.warnings.empty()) << matched.warnings.front();
  for (int k = 1; k <= 4; ++k) {
    Result<ObjMesh> other = readObj(testing::dataDir() / "cylinder" / "poses-2" / ("cylinder-" + std::to_string(k) + ".obj"));
    ASSERT_TRUE(other.ok()) << other.status().toString();
    ex->poses[static_cast<std::size_t>(k - 1)] = other->positions;
  }
  const PipelineResult mismatched = fitOrFail(*ex, PipelineOptions{});
  ASSERT_EQ(mismatched.warnings.size(), 1u);
  EXPECT_NE(mismatched.warnings[0].find("the given rig skins the bind mesh "), std::string::npos) << mismatched.warnings[0];
  expectKeysReproduced(*ex, mismatched, 1e-4);
}

TEST(FitPipeline, EqualKeysInARowAreWarnedOf) {
  Result<ExampleSet> ex = testing::cylinderWithRig(false, false);
  ASSERT_TRUE(ex.ok()) << ex.status().toString();
  ex->poses[2] = ex->poses[1];
  const PipelineResult result = fitOrFail(*ex, PipelineOptions{});
  ASSERT_EQ(result.warnings.size(), 1u);
  EXPECT_EQ(result.warnings[0], "key poses 1 and 2 (" + ex->pose_labels[1] + ", " + ex->pose_labels[2] +
                                    ") are the same shape, so the segment between them holds still");
  expectKeysReproduced(*ex, result, 1e-4);
}

TEST(FitPipeline, CylinderKabschTransformsAndDistanceWeights) {
  Result<ExampleSet> ex = testing::cylinderWithRig(false, false);
  ASSERT_TRUE(ex.ok()) << ex.status().toString();
  const PipelineResult result = fitOrFail(*ex, PipelineOptions{});
  expectKeysReproduced(*ex, result, 1e-4);
}

TEST(FitPipeline, HorseTwoFramesAutoRig) {
  const auto paths = horseFrames({1, 9});
  Result<ExampleSet> ex = readObjSequence(paths);
  ASSERT_TRUE(ex.ok()) << ex.status().toString();
  PipelineOptions options;
  options.material = skinMaterial();
  const PipelineResult result = fitOrFail(*ex, options);
  expectKeysReproduced(*ex, result, 1e-4);
}

TEST(FitPipeline, HorseKeysEveryFourFramesAreC1) {
  const auto paths = horseFrames({1, 5, 9, 13, 17, 21, 25});
  Result<ExampleSet> ex = readObjSequence(paths);
  ASSERT_TRUE(ex.ok()) << ex.status().toString();
  PipelineOptions options;
  options.material = skinMaterial();
  const PipelineResult result = fitOrFail(*ex, options);
  ASSERT_EQ(result.asset.segments.size(), 6u);
  expectKeysReproduced(*ex, result, 1e-4);
  expectC1AcrossJoins(result);
}

TEST(FitPipeline, HorseKeysEveryEightFrames) {
  const auto paths = horseFrames({1, 9, 17, 25});
  Result<ExampleSet> ex = readObjSequence(paths);
  ASSERT_TRUE(ex.ok()) << ex.status().toString();
  const PipelineResult result = fitOrFail(*ex, PipelineOptions{});
  expectKeysReproduced(*ex, result, 1e-4);
}

TEST(FitPipeline, CatPosesAutoRig) {
  const auto paths = catPoses(10);
  Result<ExampleSet> ex = readObjSequence(paths);
  ASSERT_TRUE(ex.ok()) << ex.status().toString();
  PipelineOptions options;
  options.material = skinMaterial();
  const PipelineResult result = fitOrFail(*ex, options);
  EXPECT_EQ(result.asset.vertexCount(), 7207u);
  expectKeysReproduced(*ex, result, 1e-4);
  expectC1AcrossJoins(result);
}

TEST(FitPipeline, CheburashkaWithItsRigOfElevenBones) {
  const std::filesystem::path dir = testing::dataDir() / "cheburashka";
  std::vector<std::filesystem::path> poses, tmats;
  for (int k = 1; k <= 4; ++k) {
    poses.push_back(dir / "poses-3" / ("cheburashka-" + std::to_string(k) + ".obj"));
    tmats.push_back(dir / "poses-3" / ("cheburashka-" + std::to_string(k) + ".Tmat"));
  }
  const std::filesystem::path weights = dir / "cheburashka.DMAT";
  Result<ExampleSet> ex = readLibiglExamples(dir / "cheburashka.obj", poses, dir / "cheburashka.tgf", &weights, tmats);
  ASSERT_TRUE(ex.ok()) << ex.status().toString();
  const PipelineResult result = fitOrFail(*ex, PipelineOptions{});
  expectKeysReproduced(*ex, result, 1e-4);
}

TEST(FitPipeline, FacePosesOpenSurfaceAutoRig) {
  // An open face mask (762 boundary edges) whose expressions are mostly non-rigid.
  std::vector<std::filesystem::path> paths;
  paths.reserve(3);
  for (int k = 0; k < 3; ++k) paths.push_back(testing::dataDir() / "face-poses" / ("face-0" + std::to_string(k) + ".obj"));
  Result<ExampleSet> ex = readObjSequence(paths);
  ASSERT_TRUE(ex.ok()) << ex.status().toString();
  const PipelineResult result = fitOrFail(*ex, PipelineOptions{});
  expectKeysReproduced(*ex, result, 1e-4);
}

TEST(FitPipeline, FewerAutomaticBonesThanAskedForAreReported) {
  std::vector<std::filesystem::path> paths;
  for (int k = 1; k <= 3; ++k) {
    paths.push_back(testing::dataDir() / "cylinder" / "poses-2" / ("cylinder-" + std::to_string(k) + ".obj"));
  }
  Result<ExampleSet> ex = readObjSequence(paths);
  ASSERT_TRUE(ex.ok()) << ex.status().toString();
  PipelineOptions options;
  options.auto_bones = 20;  // the cylinder's motion separates about half as many
  const PipelineResult result = fitOrFail(*ex, options);
  EXPECT_LT(result.asset.bone_names.size(), 20u);
  EXPECT_NE(result.rig_summary.find(" (20 asked for; the poses' motion separates no more) from 3 poses"), std::string::npos)
      << result.rig_summary;
}

TEST(FitPipeline, PureFourierReportsItsKeyErrorInstead) {
  const auto paths = horseFrames({1, 9});
  Result<ExampleSet> ex = readObjSequence(paths);
  ASSERT_TRUE(ex.ok());
  PipelineOptions options;
  options.pure_fourier = true;
  options.modes = 3;
  const PipelineResult result = fitOrFail(*ex, options);
  EXPECT_EQ(result.report.remainder_count, 0u);
  EXPECT_GT(result.report.key_error[1], 1e-4);  // N = 3 cannot carry a gallop's residual exactly
}

TEST(FitPipeline, PerPartMaterialsAndBadPartNames) {
  Result<ExampleSet> ex = testing::cylinderWithRig(true, true);
  ASSERT_TRUE(ex.ok());
  PipelineOptions options;
  options.part_materials["bone1"] = skinMaterial();
  options.part_materials["3"] = skinMaterial();
  const PipelineResult result = fitOrFail(*ex, options);
  EXPECT_EQ(result.asset.materials.size(), 3u);
  options.part_materials_source = "parts.json";
  options.part_materials["no-such-bone"] = skinMaterial();
  Result<PipelineResult> bad = runFitPipeline(*ex, options);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().message(), "parts.json: part 'no-such-bone' is neither a bone name nor a bone index below 4");
  // Two spellings of one bone: one material would go unused, by the map's order, not the file's.
  options.part_materials.erase("no-such-bone");
  options.part_materials["01"] = staticMaterial();
  Result<PipelineResult> twice = runFitPipeline(*ex, options);
  ASSERT_FALSE(twice.ok());
  EXPECT_EQ(twice.status().message(), "parts.json: parts '01' and 'bone1' both name bone 1; give each bone one material");
}

}  // namespace
}  // namespace odeskin
