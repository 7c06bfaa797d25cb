// SPDX-License-Identifier: MIT
#include "engine/kernels/dual_quaternion.hpp"

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "engine/kernels/lbs_job.hpp"
#include "engine/offline/rigid_transform.hpp"

namespace odeskin {
namespace {

constexpr double kPi = std::numbers::pi;

double maxAbsDiff(const BoneTransform& a, const BoneTransform& b) {
  double worst = 0.0;
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 3; ++r) worst = std::max(worst, std::fabs(a[c][r] - b[c][r]));
  }
  return worst;
}

double maxAbsDiff(const glm::dmat3& a, const glm::dmat3& b) {
  double worst = 0.0;
  for (int c = 0; c < 3; ++c) {
    for (int r = 0; r < 3; ++r) worst = std::max(worst, std::fabs(a[c][r] - b[c][r]));
  }
  return worst;
}

// Random rigid transforms, angles over the whole (-pi, pi] range so every branch of the
// matrix -> quaternion conversion (largest of w, x, y, z) is taken.
std::vector<RigidTransform> randomRigid(int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<RigidTransform> out;
  for (int k = 0; k < count; ++k) {
    const Vec3 axis = glm::normalize(Vec3(unit(rng), unit(rng), unit(rng)) + Vec3(1e-3, 0.0, 0.0));
    RigidTransform r;
    r.rotation = glm::angleAxis(kPi * unit(rng), axis);
    r.translation = 3.0 * Vec3(unit(rng), unit(rng), unit(rng));
    out.push_back(r);
  }
  return out;
}

Influences twoBones(double w0) {
  Influences in;
  in.offsets = {0, 2};
  in.bones = {0, 1};
  in.weights = {w0, 1.0 - w0};
  return in;
}

TEST(DualQuaternion, RigidRoundTrip) {
  for (const RigidTransform& r : randomRigid(200, 1)) {
    const BoneTransform m = r.matrix();
    const DualQuaternion q = DualQuaternion::fromRigid(m);
    EXPECT_NEAR(glm::length(q.real), 1.0, 1e-15);
    // A unit dual quaternion: real . dual = 0.
    EXPECT_NEAR(glm::dot(q.real, q.dual), 0.0, 1e-14);
    EXPECT_LT(maxAbsDiff(q.toRigid(), m), 1e-12);
  }
  // The half turns, where w = 0 and the conversion must pick another component.
  for (const Vec3& axis : {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1), glm::normalize(Vec3(1, -2, 3))}) {
    const BoneTransform m = rotationAbout(Vec3(0.5, -1.0, 2.0), axis, kPi).matrix();
    EXPECT_LT(maxAbsDiff(DualQuaternion::fromRigid(m).toRigid(), m), 1e-12);
  }
}

TEST(DualQuaternion, NearestRotationIsThePolarFactor) {
  // R S with S symmetric positive definite has polar factor R.
  const glm::dmat3 r = glm::mat3_cast(glm::angleAxis(1.1, glm::normalize(Vec3(1.0, 2.0, -0.5))));
  const glm::dmat3 s(1.3, 0.2, -0.1, 0.2, 0.8, 0.15, -0.1, 0.15, 1.1);  // eigenvalues > 0
  EXPECT_LT(maxAbsDiff(nearestRotation(r * s), r), 1e-12);
  EXPECT_LT(maxAbsDiff(nearestRotation(r), r), 1e-15);
  // fromRigid drops the stretch of an affine bone and keeps its translation.
  const BoneTransform affine(r * s);
  BoneTransform with_translation = affine;
  with_translation[3] = Vec3(1.0, 2.0, 3.0);
  const BoneTransform rigid = DualQuaternion::fromRigid(with_translation).toRigid();
  EXPECT_LT(maxAbsDiff(glm::dmat3(rigid), r), 1e-12);
  EXPECT_LT(glm::length(rigid[3] - Vec3(1.0, 2.0, 3.0)), 1e-12);
}

TEST(DualQuaternion, NearestRotationOfNoRotationIsStillARotation) {
  const glm::dmat3 mirror(-1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0);
  const glm::dmat3 fixed = nearestRotation(mirror);
  EXPECT_NEAR(glm::determinant(fixed), 1.0, 1e-15);
  EXPECT_LT(maxAbsDiff(glm::transpose(fixed) * fixed, glm::dmat3(1.0)), 1e-15);
  EXPECT_EQ(nearestRotation(glm::dmat3(0.0)), glm::dmat3(1.0));
  EXPECT_EQ(nearestRotation(glm::dmat3(std::nan(""))), glm::dmat3(1.0));
}

// The property LBS lacks: bones that all rotate about one joint c blend, under DQS, to a rotation
// about c (the dual part of a rotation about c is linear in its real part), so every vertex keeps
// its distance to the joint, whatever the weights and axes. LBS averages the rotated points and
// pulls them towards the joint: at w = 1/2 and an angle theta between the two bones, a point
// perpendicular to the axis ends at radius cos(theta / 2), the candy wrapper at theta = pi.
TEST(DualQuaternion, BlendAboutAJointKeepsTheJointRadius) {
  const Vec3 joint(0.3, -1.2, 0.7);
  const Vec3 axis(1.0, 0.0, 0.0);  // a twist about the limb's axis
  const double radius = 0.4;
  for (double angle : {kPi / 4, kPi / 2, 5 * kPi / 6, 0.99 * kPi}) {
    const std::vector<BoneTransform> bones{rotationAbout(joint, axis, 0.0).matrix(),
                                           rotationAbout(joint, axis, angle).matrix()};
    const Influences in = twoBones(0.5);
    for (double around : {0.0, 1.0, 2.5}) {
      const Vec3 x = joint + radius * Vec3(0.0, std::cos(around), std::sin(around));
      const Vec3 dqs = skinTransform(SkinningMode::kDualQuaternion, in, bones, 0).apply(x);
      const Vec3 lbs = skinTransform(SkinningMode::kLinear, in, bones, 0).apply(x);
      EXPECT_NEAR(glm::length(dqs - joint), radius, 1e-12) << "angle " << angle;
      EXPECT_NEAR(glm::length(lbs - joint), radius * std::cos(angle / 2), 1e-12) << "angle " << angle;
      // Halfway by symmetry: the twist by angle / 2.
      EXPECT_LT(glm::length(dqs - rotationAbout(joint, axis, angle / 2).apply(x)), 1e-12);
    }
  }
  // Any weights, any axes through the joint, any point.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int k = 0; k < 100; ++k) {
    std::vector<BoneTransform> bones;
    for (int b = 0; b < 3; ++b) {
      const Vec3 a = glm::normalize(Vec3(unit(rng), unit(rng), unit(rng)) + Vec3(0.0, 1e-3, 0.0));
      bones.push_back(rotationAbout(joint, a, 1.5 * unit(rng)).matrix());
    }
    Influences in;
    in.offsets = {0, 3};
    in.bones = {0, 1, 2};
    const double w0 = 0.5 * (1.0 + unit(rng)), w1 = 0.5 * (1.0 - w0) * (1.0 + unit(rng));
    in.weights = {w0, w1, 1.0 - w0 - w1};
    const Vec3 x = joint + Vec3(unit(rng), unit(rng), unit(rng));
    const SkinTransform t = skinTransform(SkinningMode::kDualQuaternion, in, bones, 0);
    EXPECT_NEAR(glm::length(t.apply(x) - joint), glm::length(x - joint), 1e-12);
    EXPECT_NEAR(glm::determinant(t.linear), 1.0, 1e-12);
  }
}

// q and -q are the same rotation. Rotations by +170 and -170 degrees about z are 20 degrees apart
// through the half turn, but their quaternions with w = cos 85 degrees > 0 have a negative dot
// product: blended as given they average the long way round, to no rotation at all.
TEST(DualQuaternion, AntipodalQuaternionsBlendTheShortWay) {
  const Vec3 z(0.0, 0.0, 1.0);
  const std::vector<BoneTransform> bones{rotationAbout(Vec3(0.0), z, 170.0 / 180.0 * kPi).matrix(),
                                         rotationAbout(Vec3(0.0), z, -170.0 / 180.0 * kPi).matrix()};
  std::vector<DualQuaternion> q = toDualQuaternions(bones);
  // fromRigid may return either sign; take the w > 0 ones, which are antipodal here.
  for (DualQuaternion& d : q) {
    if (d.real.w < 0.0) d = DualQuaternion{-d.real, -d.dual};
  }
  ASSERT_LT(glm::dot(q[0].real, q[1].real), 0.0) << "the test needs antipodal inputs";
  const Vec3 x(1.0, 0.0, 0.0);
  const Vec3 halfway = skinTransform(SkinningMode::kDualQuaternion, twoBones(0.5), bones, q, 0).apply(x);
  EXPECT_LT(glm::length(halfway - Vec3(-1.0, 0.0, 0.0)), 1e-12);  // the half turn
  // Without the sign fix the same weights give the identity (the long way round).
  const glm::dquat naive = glm::normalize(0.5 * q[0].real + 0.5 * q[1].real);
  EXPECT_LT(glm::length(naive * x - x), 1e-12);

  // The result does not depend on the sign either bone's quaternion happens to have, and the pivot
  // (largest weight) may itself be the flipped one.
  for (double w0 : {0.2, 0.5, 0.8}) {
    const Influences in = twoBones(w0);
    const SkinTransform expected = skinTransform(SkinningMode::kDualQuaternion, in, bones, q, 0);
    for (int flip = 1; flip < 4; ++flip) {
      std::vector<DualQuaternion> signs = q;
      for (int b = 0; b < 2; ++b) {
        if (flip & (1 << b)) signs[b] = DualQuaternion{-q[b].real, -q[b].dual};
      }
      const SkinTransform got = skinTransform(SkinningMode::kDualQuaternion, in, bones, signs, 0);
      EXPECT_LT(maxAbsDiff(got.linear, expected.linear), 1e-14) << "w0 " << w0 << " flip " << flip;
      EXPECT_LT(glm::length(got.translation - expected.translation), 1e-14);
    }
    // And it lies between the bones, on the short arc through the half turn: near 190 - 20 w0
    // degrees (not exactly: the blend is an nlerp, within 0.1 degree of slerp over 20 degrees).
    const Vec3 y = expected.apply(x);
    const double target = (190.0 - 20.0 * w0) / 180.0 * kPi;
    EXPECT_LT(std::fabs(std::remainder(std::atan2(y.y, y.x) - target, 2 * kPi)), 0.1 / 180.0 * kPi) << "w0 " << w0;
  }
}

TEST(DualQuaternion, LinearModeIsLbs) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<BoneTransform> bones;
  for (const RigidTransform& r : randomRigid(4, 9)) bones.push_back(r.matrix());
  bones[2][0] *= 1.3;  // affine is fine for LBS
  Influences in;
  in.offsets = {0, 3};
  in.bones = {0, 2, 3};
  in.weights = {0.2, 0.5, 0.3};
  const SkinTransform t = skinTransform(SkinningMode::kLinear, in, bones, 0);
  EXPECT_LT(maxAbsDiff(t.linear, blendedLinearPart(in, bones, 0)), 1e-15);
  for (int k = 0; k < 10; ++k) {
    const Vec3 x(unit(rng), unit(rng), unit(rng));
    EXPECT_LT(glm::length(t.apply(x) - skinPoint(in, bones, 0, x)), 1e-14);
  }
}

TEST(DualQuaternion, PerVertexAndPrecomputedOverloadsAgree) {
  std::vector<BoneTransform> bones;
  for (const RigidTransform& r : randomRigid(5, 11)) bones.push_back(r.matrix());
  Influences in;
  in.offsets = {0, 1, 4, 6};
  in.bones = {3, 0, 4, 1, 2, 4};
  in.weights = {1.0, 0.2, 0.5, 0.3, 0.6, 0.4};
  const std::vector<DualQuaternion> q = toDualQuaternions(bones);
  for (std::size_t i = 0; i < 3; ++i) {
    const SkinTransform a = skinTransform(SkinningMode::kDualQuaternion, in, bones, i);
    const SkinTransform b = skinTransform(SkinningMode::kDualQuaternion, in, bones, q, i);
    EXPECT_LT(maxAbsDiff(a.linear, b.linear), 1e-15);
    EXPECT_LT(glm::length(a.translation - b.translation), 1e-15);
  }
  // A single influence reproduces its bone exactly.
  const SkinTransform single = skinTransform(SkinningMode::kDualQuaternion, in, bones, q, 0);
  EXPECT_LT(maxAbsDiff(BoneTransform(single.linear[0], single.linear[1], single.linear[2], single.translation),
                       bones[3]),
            1e-12);
}

// Weights that do not blend to a rotation (here all zero, which validateInfluences rejects) fall
// back to LBS for that vertex instead of dividing by zero.
TEST(DualQuaternion, DegenerateBlendFallsBackToLbs) {
  std::vector<BoneTransform> bones;
  for (const RigidTransform& r : randomRigid(2, 13)) bones.push_back(r.matrix());
  Influences in;
  in.offsets = {0, 2, 2};
  in.bones = {0, 1};
  in.weights = {0.0, 0.0};
  const std::vector<DualQuaternion> q = toDualQuaternions(bones);
  EXPECT_FALSE(blendDualQuaternions(in, q, 0).has_value());
  EXPECT_FALSE(blendDualQuaternions(in, q, 1).has_value());  // no influence at all
  for (std::size_t i = 0; i < 2; ++i) {
    const SkinTransform t = skinTransform(SkinningMode::kDualQuaternion, in, bones, q, i);
    EXPECT_EQ(t.linear, glm::dmat3(0.0));
    EXPECT_EQ(t.translation, Vec3(0.0));
  }
}

}  // namespace
}  // namespace odeskin
