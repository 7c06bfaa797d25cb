// SPDX-License-Identifier: MIT
#include "engine/offline/rigid_transform.hpp"

#include <random>

#include <gtest/gtest.h>

namespace odeskin {
namespace {

std::vector<RigidTransform> randomKeys(std::size_t count, std::uint32_t seed, const Vec3& pivot) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<RigidTransform> keys;
  double angle = 0.0;
  for (std::size_t k = 0; k < count; ++k) {
    angle += 0.9 * u(rng);  // up to ~50 degrees between keys, about a wandering axis
    RigidTransform key = rotationAbout(pivot, Vec3(u(rng), u(rng), 1.0), angle);
    key.translation += 0.3 * Vec3(u(rng), u(rng), u(rng));
    keys.push_back(key);
  }
  return keys;
}

// Velocity of a point at the join between segment s-1 and s, from one-sided differences.
std::pair<Vec3, Vec3> velocityAtKey(const RigidKeyPath& path, std::uint32_t s, const Vec3& x, double h) {
  const Vec3 before = (path.at(s - 1, 1.0).apply(x) - path.at(s - 1, 1.0 - h).apply(x)) / h;
  const Vec3 after = (path.at(s, h).apply(x) - path.at(s, 0.0).apply(x)) / h;
  return {before, after};
}

TEST(RigidKeyPath, TwoKeysIsInterpolateRigid) {
  const Vec3 pivot(0.4, -0.2, 0.1);
  const auto keys = randomKeys(2, 3, pivot);
  const RigidKeyPath path(keys, pivot);
  for (double tau : {0.0, 0.25, 0.5, 0.9, 1.0}) {
    const RigidTransform a = path.at(0, tau);
    const RigidTransform b = interpolateRigid(keys[0], keys[1], tau, pivot);
    for (const Vec3& x : {Vec3(0.0), Vec3(1.0, 2.0, -1.0), pivot}) {
      EXPECT_LT(glm::length(a.apply(x) - b.apply(x)), 1e-12) << "tau " << tau;
    }
  }
}

TEST(RigidKeyPath, PassesThroughEveryKey) {
  const Vec3 pivot(0.0, 1.0, 0.0);
  const auto keys = randomKeys(6, 7, pivot);
  const RigidKeyPath path(keys, pivot);
  const Vec3 x(0.3, 0.5, -0.8);
  for (std::uint32_t k = 0; k < 6; ++k) {
    const RigidTransform at = k < 5 ? path.at(k, 0.0) : path.at(4, 1.0);
    EXPECT_LT(glm::length(at.apply(x) - keys[k].apply(x)), 1e-12) << "key " << k;
  }
}

TEST(RigidKeyPath, VelocityIsContinuousAtKeysWherePiecewiseSlerpJumps) {
  const Vec3 pivot(0.2, 0.0, 0.0);
  const Vec3 x(1.2, 0.4, -0.3);
  const double h = 1e-6;
  for (std::uint32_t seed : {1u, 2u, 3u, 4u}) {
    const auto keys = randomKeys(5, seed, pivot);
    const RigidKeyPath path(keys, pivot);
    for (std::uint32_t s = 1; s < 4; ++s) {
      const auto [before, after] = velocityAtKey(path, s, x, h);
      EXPECT_LT(glm::length(after - before), 1e-4 * (1.0 + glm::length(before))) << "seed " << seed << " key " << s;
      // The K = 2 scheme per segment has a corner at the key: the test would see it.
      const Vec3 slerp_before =
          (keys[s].apply(x) - interpolateRigid(keys[s - 1], keys[s], 1.0 - h, pivot).apply(x)) / h;
      const Vec3 slerp_after = (interpolateRigid(keys[s], keys[s + 1], h, pivot).apply(x) - keys[s].apply(x)) / h;
      EXPECT_GT(glm::length(slerp_after - slerp_before), 1e-2) << "seed " << seed << " key " << s;
    }
  }
}

}  // namespace
}  // namespace odeskin
