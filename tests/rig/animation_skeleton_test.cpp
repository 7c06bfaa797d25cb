// SPDX-License-Identifier: MIT
#include "engine/rig/animation_skeleton.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

namespace odeskin {
namespace {

// A chain of `count` nodes 0.1 apart along x (node 0 at the middle, as the curve skeleton hangs
// from its centre ring: nodes 1.. go left, then the right half), radius 0.05 everywhere.
struct Chain {
  CurveSkeleton skeleton;
  std::vector<std::uint32_t> order;  // nodes from the left end to the right end
};

Chain straightChain(int half) {
  Chain c;
  CurveSkeleton& s = c.skeleton;
  auto add = [&](const Vec3& p, std::int32_t parent) {
    s.positions.push_back(p);
    s.radii.push_back(0.05);
    s.kinds.push_back(parent < 0 ? SkeletonNodeKind::kRoot : SkeletonNodeKind::kCurve);
    s.parents.push_back(parent);
    s.parts.push_back(0);
    s.anchor_offsets.push_back(0);
  };
  add(Vec3(0.0), -1);
  std::vector<std::uint32_t> left, right;
  for (int side : {-1, 1}) {
    std::int32_t parent = 0;
    for (int k = 1; k <= half; ++k) {
      add(Vec3(0.1 * side * k, 0.0, 0.0), parent);
      parent = static_cast<std::int32_t>(s.nodeCount() - 1);
      (side < 0 ? left : right).push_back(static_cast<std::uint32_t>(parent));
    }
  }
  // cppcheck-suppress containerOutOfBounds ; every caller passes half >= 1, so both sides hold nodes
  s.kinds[left.back()] = s.kinds[right.back()] = SkeletonNodeKind::kTip;
  c.order.assign(left.rbegin(), left.rend());
  c.order.push_back(0);
  c.order.insert(c.order.end(), right.begin(), right.end());
  return c;
}

// The chain's node positions with the part right of arc position `at` (an index into order)
// turned by `deg` degrees about z.
std::vector<Vec3> bentAt(const Chain& c, std::size_t at, double deg) {
  std::vector<Vec3> p = c.skeleton.positions;
  const double a = deg * std::numbers::pi / 180.0;
  const Vec3 pivot = p[c.order[at]];
  for (std::size_t i = at + 1; i < c.order.size(); ++i) {
    const Vec3 d = p[c.order[i]] - pivot;
    p[c.order[i]] = pivot + Vec3(std::cos(a) * d.x - std::sin(a) * d.y, std::sin(a) * d.x + std::cos(a) * d.y, d.z);
  }
  return p;
}

std::vector<std::int32_t> bendNodes(const AnimationSkeleton& a) {
  std::vector<std::int32_t> nodes;
  for (std::size_t j = 0; j < a.jointCount(); ++j) {
    if (a.reasons[j] == JointReason::kBend) nodes.push_back(a.nodes[j]);
  }
  return nodes;
}

TEST(AnimationSkeleton, RejectsBadInput) {
  const Chain c = straightChain(10);
  EXPECT_EQ(buildAnimationSkeleton(CurveSkeleton{}, {{}}).status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(buildAnimationSkeleton(c.skeleton, {}).status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(buildAnimationSkeleton(c.skeleton, {{Vec3(0.0)}}).status().code(), StatusCode::kInvalidArgument);
  AnimationSkeletonOptions o;
  o.angle_threshold_deg = 0.0;
  EXPECT_EQ(buildAnimationSkeleton(c.skeleton, {c.skeleton.positions}, o).status().code(), StatusCode::kInvalidArgument);
  o = {};
  o.up = Vec3(0.0);
  EXPECT_EQ(buildAnimationSkeleton(c.skeleton, {c.skeleton.positions}, o).status().code(), StatusCode::kInvalidArgument);
  CurveSkeleton looped = c.skeleton;
  looped.parents[3] = 5;  // a parent after its child
  EXPECT_EQ(buildAnimationSkeleton(looped, {looped.positions}).status().code(), StatusCode::kInvalidArgument);
}

TEST(AnimationSkeleton, StraightChainHasOnlyItsEnds) {
  const Chain c = straightChain(10);
  Result<AnimationSkeleton> a = buildAnimationSkeleton(c.skeleton, {c.skeleton.positions});
  ASSERT_TRUE(a.ok()) << a.status().message();
  EXPECT_TRUE(bendNodes(*a).empty());
  // The root (the centre node: no junction, no bend) and the two tips: two bones.
  EXPECT_EQ(a->jointCount(), 3u);
  EXPECT_EQ(a->reasons[0], JointReason::kRoot);
  const Skeleton s = toSkeleton(*a);
  ASSERT_EQ(s.boneCount(), 2u);
  EXPECT_EQ(s.parents[0], -1);
  EXPECT_EQ(s.parents[1], -1);
  EXPECT_EQ(s.heads[0], a->joints[0]);
}

TEST(AnimationSkeleton, BentBindPoseGetsAJointAtTheBend) {
  const Chain c = straightChain(10);
  CurveSkeleton bent = c.skeleton;
  bent.positions = bentAt(c, 15, 60.0);  // order index 15: the fifth node right of the centre
  Result<AnimationSkeleton> a = buildAnimationSkeleton(bent, {bent.positions});
  ASSERT_TRUE(a.ok());
  const std::vector<std::int32_t> bends = bendNodes(*a);
  ASSERT_EQ(bends.size(), 1u);
  EXPECT_EQ(bends[0], static_cast<std::int32_t>(c.order[15]));
  // 10 degrees is under the threshold.
  bent.positions = bentAt(c, 15, 10.0);
  EXPECT_TRUE(bendNodes(*buildAnimationSkeleton(bent, {bent.positions})).empty());
}

TEST(AnimationSkeleton, ExamplePosesPlaceJointsTheBindPoseDoesNotShow) {
  const Chain c = straightChain(10);
  // Sec. 5.4: the bind pose is straight; one pose bends at order 5, another at 15.
  Result<AnimationSkeleton> a =
      buildAnimationSkeleton(c.skeleton, {c.skeleton.positions, bentAt(c, 5, 45.0), bentAt(c, 15, 45.0)});
  ASSERT_TRUE(a.ok());
  std::vector<std::int32_t> bends = bendNodes(*a);
  std::sort(bends.begin(), bends.end());
  std::vector<std::int32_t> expected{static_cast<std::int32_t>(c.order[5]), static_cast<std::int32_t>(c.order[15])};
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(bends, expected);
}

TEST(AnimationSkeleton, LargerBendWinsWherePosesDisagree) {
  const Chain c = straightChain(10);
  // Two poses put the joint one node apart (closer than the window): the larger turn wins.
  for (const bool first_larger : {true, false}) {
    Result<AnimationSkeleton> a = buildAnimationSkeleton(
        c.skeleton, {c.skeleton.positions, bentAt(c, 14, first_larger ? 70.0 : 35.0), bentAt(c, 15, first_larger ? 35.0 : 70.0)});
    ASSERT_TRUE(a.ok());
    const std::vector<std::int32_t> bends = bendNodes(*a);
    ASSERT_EQ(bends.size(), 1u);
    EXPECT_EQ(bends[0], static_cast<std::int32_t>(c.order[first_larger ? 14 : 15]));
    for (std::size_t j = 0; j < a->jointCount(); ++j) {
      if (a->reasons[j] == JointReason::kBend) {
        EXPECT_NEAR(a->bend_deg[j], 70.0, 1e-6);
      }
    }
  }
}

TEST(AnimationSkeleton, BonesChainFromTheRoot) {
  const Chain c = straightChain(10);
  Result<AnimationSkeleton> a = buildAnimationSkeleton(c.skeleton, {c.skeleton.positions, bentAt(c, 15, 45.0)});
  ASSERT_TRUE(a.ok());
  const Skeleton s = toSkeleton(*a);
  ASSERT_EQ(s.boneCount(), a->jointCount() - 1);
  ASSERT_TRUE(validateRig(Rig{s, {}, {}}, 0, 0).ok());
  for (std::size_t b = 0; b < s.boneCount(); ++b) {
    if (s.parents[b] >= 0) {
      EXPECT_LT(s.parents[b], static_cast<std::int32_t>(b));
      EXPECT_EQ(s.heads[b], s.tails[static_cast<std::size_t>(s.parents[b])]);  // a child starts where its parent ends
    } else {
      EXPECT_EQ(s.heads[b], a->joints[0]);
    }
  }
}

}  // namespace
}  // namespace odeskin
