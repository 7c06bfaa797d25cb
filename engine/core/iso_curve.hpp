// SPDX-License-Identifier: MIT
// An iso-parametric curve on the bind mesh (thesis 6.3): points that lie on mesh edges (a plane
// cut) or on vertices (snapped, or a quad edge loop). A point's position in any pose is the same
// edge ratio of that pose's edge (thesis Fig. 6.6), so one curve serves every example pose.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "types.hpp"

namespace odeskin {

// (1 - t) X_a + t X_b; a == b and t == 0 for a point on vertex a.
struct CurvePoint {
  std::uint32_t a = 0;
  std::uint32_t b = 0;
  double t = 0.0;
};

struct IsoCurve {
  std::vector<CurvePoint> points;  // in order along the curve; a closed curve does not repeat its first point
  std::vector<double> v;           // per point: arc-length parameter on the bind mesh (MATH.md 4.1)
  bool closed = true;
  std::uint32_t part = 0;          // body part (a bone index) the curve belongs to, for per-part materials
};

inline Vec3 curvePointPosition(std::span<const Vec3> positions, const CurvePoint& p) {
  return (1.0 - p.t) * positions[p.a] + p.t * positions[p.b];
}

}  // namespace odeskin
