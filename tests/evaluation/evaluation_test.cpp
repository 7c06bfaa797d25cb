// SPDX-License-Identifier: MIT
// runEvaluation's bookkeeping: which frames are in-betweens and at what (segment, tau), and the
// input errors it must report before any fitting (bad keys or times, mismatched meshes, methods).
#include <gtest/gtest.h>

#include "engine/evaluation/evaluation.hpp"

namespace odeskin {
namespace {

TEST(Evaluation, InBetweensAreUniformInFrameIndexWithinEachSegment) {
  const std::vector<std::uint32_t> keys{0, 4, 6};
  Result<std::vector<InBetween>> ib = inBetweenFrames(8, keys, {});
  ASSERT_TRUE(ib.ok()) << ib.status().toString();
  ASSERT_EQ(ib->size(), 4u);  // 1, 2, 3 and 5; frame 7 lies after the last key
  EXPECT_EQ((*ib)[0].frame, 1u);
  EXPECT_EQ((*ib)[0].segment, 0u);
  EXPECT_DOUBLE_EQ((*ib)[0].tau, 0.25);
  EXPECT_DOUBLE_EQ((*ib)[2].tau, 0.75);
  EXPECT_EQ((*ib)[3].frame, 5u);
  EXPECT_EQ((*ib)[3].segment, 1u);
  EXPECT_DOUBLE_EQ((*ib)[3].tau, 0.5);
}

TEST(Evaluation, TimesPlaceTheInBetweens) {
  const std::vector<std::uint32_t> keys{0, 2};
  const std::vector<double> times{0.0, 0.1, 1.0};
  Result<std::vector<InBetween>> ib = inBetweenFrames(3, keys, times);
  ASSERT_TRUE(ib.ok());
  ASSERT_EQ(ib->size(), 1u);
  EXPECT_DOUBLE_EQ((*ib)[0].tau, 0.1);
}

TEST(Evaluation, RejectsBadKeysAndTimes) {
  const auto message = [](const std::vector<std::uint32_t>& keys, const std::vector<double>& times = {}) {
    Result<std::vector<InBetween>> ib = inBetweenFrames(5, keys, times);
    EXPECT_FALSE(ib.ok());
    return ib.ok() ? std::string() : ib.status().message();
  };
  EXPECT_NE(message({2}).find("at least 2"), std::string::npos);
  EXPECT_NE(message({3, 1}).find("strictly increasing"), std::string::npos);
  EXPECT_NE(message({1, 1}).find("strictly increasing"), std::string::npos);
  EXPECT_NE(message({0, 5}).find("key 5 is out of range"), std::string::npos);
  EXPECT_NE(message({0, 4}, {0, 1, 2}).find("3 times for 5 frames"), std::string::npos);
  EXPECT_NE(message({0, 4}, {0, 1, 1, 2, 3}).find("strictly increasing"), std::string::npos);
}

TEST(Evaluation, RejectsMismatchedMeshesNamingTheFile) {
  ExampleSet frames;
  frames.poses = {std::vector<Vec3>(4), std::vector<Vec3>(4), std::vector<Vec3>(3)};
  frames.pose_labels = {"a.obj", "b.obj", "c.obj"};
  const std::vector<std::uint32_t> keys{0, 2};
  const std::vector<BaselineMethod> methods{BaselineMethod::kLinear};
  Result<EvaluationResult> r = runEvaluation(frames, keys, methods, PoseSource::kTruth, {});
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(r.status().message().find("c.obj: 3 vertices but a.obj has 4"), std::string::npos) << r.status().message();
}

TEST(Evaluation, RejectsEmptyOrRepeatedMethods) {
  ExampleSet frames;
  frames.poses = {std::vector<Vec3>(4), std::vector<Vec3>(4), std::vector<Vec3>(4)};
  const std::vector<std::uint32_t> keys{0, 2};
  EXPECT_FALSE(runEvaluation(frames, keys, {}, PoseSource::kKeys, {}).ok());
  const std::vector<BaselineMethod> twice{BaselineMethod::kLbs, BaselineMethod::kLbs};
  Result<EvaluationResult> r = runEvaluation(frames, keys, twice, PoseSource::kKeys, {});
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("lbs is listed twice"), std::string::npos);
}

TEST(Evaluation, PoseSourceNamesRoundTrip) {
  for (const PoseSource s : {PoseSource::kTruth, PoseSource::kKeys}) {
    PoseSource parsed{};
    ASSERT_TRUE(parsePoseSource(poseSourceName(s), &parsed));
    EXPECT_EQ(parsed, s);
  }
  PoseSource ignored{};
  EXPECT_FALSE(parsePoseSource("bones", &ignored));
}

}  // namespace
}  // namespace odeskin
