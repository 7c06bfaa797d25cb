// SPDX-License-Identifier: MIT
// A procedural two-bone arm (procedural_arm.hpp) bent through several key angles, with a biceps
// bulge proportional to the bend: every pose is LBS(X + bulge(theta)) with known bones, so the
// exact in-between at any angle is known, and the bind-space corrective is linear in the angle.
#pragma once

#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "engine/offline/procedural_arm.hpp"
#include "engine/offline/residual_fit.hpp"

namespace odeskin::testing {

struct ArmKeys {
  DeformAsset asset;
  std::vector<std::vector<Vec3>> keys;  // K x V
  std::vector<double> bends;            // K, degrees
};

// Bulge amplitude (fraction of the radius) at bend `degrees`, linear in the angle.
inline double armBulge(double degrees, double bulge_at_100) { return bulge_at_100 * degrees / 100.0; }

inline ArmOptions armOptions(double degrees, double bulge_at_100) {
  ArmOptions o;
  o.rings = 21;
  o.ring_vertices = 24;
  o.bend_degrees = degrees;
  o.bulge = armBulge(degrees, bulge_at_100);
  return o;
}

// The exact arm at `degrees` and its two bones (upper arm fixed, forearm turned about the elbow).
inline std::vector<Vec3> armPose(double degrees, double bulge_at_100) {
  Result<ProceduralArm> arm = makeProceduralArm(armOptions(degrees, bulge_at_100));
  EXPECT_TRUE(arm.ok());
  return arm.ok() ? arm->end_positions : std::vector<Vec3>{};
}

inline std::vector<BoneTransform> armBones(double degrees) {
  const Vec3 elbow(0.5, 0.0, 0.0);
  return {RigidTransform{}.matrix(),
          rotationAbout(elbow, Vec3(0.0, 0.0, 1.0), degrees * std::numbers::pi / 180.0).matrix()};
}

// Keys at `bends` (degrees, first usually 0), fitted with N modes and `material`.
inline ArmKeys makeArmKeys(const std::vector<double>& bends, double bulge_at_100, int modes = 5,
                           const Material& material = staticMaterial()) {
  ArmKeys out;
  out.bends = bends;
  Result<ProceduralArm> base = makeProceduralArm(armOptions(bends.front(), bulge_at_100));
  EXPECT_TRUE(base.ok());
  FitInput in = base->fit_input;
  in.poses.clear();
  in.key_poses.clear();
  const Vec3 elbow = in.bone_pivots[1];
  for (double degrees : bends) {
    out.keys.push_back(armPose(degrees, bulge_at_100));
    in.poses.push_back(out.keys.back());
    in.key_poses.push_back({RigidTransform{}, rotationAbout(elbow, Vec3(0.0, 0.0, 1.0), degrees * std::numbers::pi / 180.0)});
  }
  FitOptions options;
  options.modes = modes;
  options.materials = {material};
  Result<DeformAsset> asset = fitDeformAsset(in, options);
  EXPECT_TRUE(asset.ok()) << asset.status().toString();
  if (asset.ok()) out.asset = std::move(*asset);
  return out;
}

inline double maxDistance(std::span<const Vec3> a, std::span<const Vec3> b) {
  double worst = 0.0;
  for (std::size_t i = 0; i < a.size() && i < b.size(); ++i) worst = std::max(worst, glm::length(a[i] - b[i]));
  return worst;
}

}  // namespace odeskin::testing
