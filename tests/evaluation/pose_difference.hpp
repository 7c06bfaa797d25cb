// SPDX-License-Identifier: MIT
// What the evaluation tests compare: a method played at (segment, tau) under given bones, and the
// per-vertex distance between two such meshes relative to the bounding box's longest side.
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include <gtest/gtest.h>

#include "engine/baselines/baseline.hpp"

namespace odeskin::testing {

struct Difference {
  double max = 0.0;   // / Lbox
  double mean = 0.0;  // / Lbox
};

inline Difference difference(std::span<const Vec3> a, std::span<const Vec3> b, double box) {
  Difference d;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double e = glm::length(a[i] - b[i]) / box;
    d.max = std::max(d.max, e);
    d.mean += e / static_cast<double>(a.size());
  }
  return d;
}

inline std::vector<Vec3> play(Baseline& method, std::uint32_t segment, double tau, std::span<const BoneTransform> bones) {
  std::vector<Vec3> out(method.vertexCount());
  const Status st = method.evaluate({segment, tau, bones}, out);
  EXPECT_TRUE(st.ok()) << st.toString();
  return out;
}

}  // namespace odeskin::testing
