// SPDX-License-Identifier: MIT
#include "engine/rig/rig.hpp"

#include <limits>
#include <string>

#include <gtest/gtest.h>

namespace odeskin {
namespace {

// Two bones in a chain, bound to two vertices, with transforms for two example poses.
Rig twoBoneRig() {
  Rig rig;
  rig.skeleton.parents = {-1, 0};
  rig.skeleton.heads = {Vec3(0.0), Vec3(1.0, 0.0, 0.0)};
  rig.skeleton.tails = {Vec3(1.0, 0.0, 0.0), Vec3(2.0, 0.0, 0.0)};
  rig.influences.offsets = {0, 1, 2};
  rig.influences.bones = {0, 1};
  rig.influences.weights = {1.0, 1.0};
  rig.key_poses.assign(2, std::vector<RigidTransform>(2));
  return rig;
}

void expectRefused(const Rig& rig, const std::string& message) {
  const Status s = validateRig(rig, 2, 2);
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument) << s.toString();
  EXPECT_NE(s.message().find(message), std::string::npos) << s.message();
}

TEST(ValidateRig, AcceptsAConsistentRig) { EXPECT_TRUE(validateRig(twoBoneRig(), 2, 2).ok()); }

TEST(ValidateRig, RefusesSkeletonArraysOfDifferentSizes) {
  Rig rig = twoBoneRig();
  rig.skeleton.parents.pop_back();
  expectRefused(rig, "skeleton arrays differ in size (heads 2, tails 2, parents 1, names 0)");
  rig = twoBoneRig();
  rig.skeleton.names = {"only one"};
  expectRefused(rig, "names 1)");
}

TEST(ValidateRig, RefusesAParentOutsideTheSkeleton) {
  Rig rig = twoBoneRig();
  rig.skeleton.parents[1] = 2;
  expectRefused(rig, "bone 1 has parent 2 outside -1..1");
  rig.skeleton.parents[1] = -2;
  expectRefused(rig, "bone 1 has parent -2 outside -1..1");
}

TEST(ValidateRig, RefusesTransformsThatDoNotMatchThePosesOrTheBones) {
  Rig rig = twoBoneRig();
  rig.key_poses.emplace_back(2);
  expectRefused(rig, "3 sets of bone transforms for 2 example poses");
  rig = twoBoneRig();
  rig.key_poses[1].pop_back();
  expectRefused(rig, "pose 1 has 1 bone transforms for 2 bones");
}

TEST(ValidateRig, RefusesARotationThatIsNotUnitOrATranslationThatIsNotFinite) {
  Rig rig = twoBoneRig();
  rig.key_poses[0][1].rotation = glm::dquat(2.0, 0.0, 0.0, 0.0);
  expectRefused(rig, "pose 0 bone 1 has a non-finite transform or a rotation that is not unit");
  rig = twoBoneRig();
  rig.key_poses[1][0].translation.y = std::numeric_limits<double>::quiet_NaN();
  expectRefused(rig, "pose 1 bone 0 has a non-finite transform");
}

TEST(ValidateRig, ChecksTransformsAndWeightsOnlyWhenAskedTo) {
  // Counts of 0 skip the per-pose and per-vertex checks (a skeleton read on its own).
  Rig rig = twoBoneRig();
  rig.key_poses.emplace_back(2);
  rig.influences.bones[1] = 7;
  EXPECT_TRUE(validateRig(rig, 0, 0).ok());
  EXPECT_FALSE(validateRig(rig, 2, 0).ok()) << "bone 7 of 2 in the weights";
}

}  // namespace
}  // namespace odeskin
