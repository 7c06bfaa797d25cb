// SPDX-License-Identifier: MIT
// A procedural arm: a tapered tube of quads along +x with an elbow, two bones (upper arm, forearm)
// and smooth weights. The end pose bends the forearm about the elbow and bulges the biceps, so the
// whole pipeline runs on data whose iso-curves (the rings) and parameters v = j/J are exactly known.
#pragma once

#include <cstdint>
#include <vector>

#include "../core/result.hpp"
#include "residual_fit.hpp"

namespace odeskin {

struct ArmOptions {
  std::uint32_t rings = 41;          // cross-sections along the arm (>= 3)
  std::uint32_t ring_vertices = 32;  // J, vertices per ring (>= 3; >= 2N+1 to fit N modes)
  std::uint32_t curve_stride = 2;    // every curve_stride-th ring is a fitted curve; rings between blend
  double length = 1.0;               // shoulder at x = 0, hand at x = length, elbow at length / 2
  double radius = 0.08;
  double bend_degrees = 100.0;       // forearm rotation about the elbow (z axis) in the end pose
  double bulge = 0.35;               // biceps bulge amplitude, as a fraction of the radius
  double blend_width = 0.08;         // half-width of the elbow weight blend, as a fraction of length
};

struct ProceduralArm {
  FitInput fit_input;                // rest mesh, both poses, rig, curves, bindings
  std::vector<Vec3> start_positions; // pose 0 (= rest)
  std::vector<Vec3> end_positions;   // pose 1
};

// kInvalidArgument naming the option out of range (counts too small, non-positive sizes, NaN).
Result<ProceduralArm> makeProceduralArm(const ArmOptions& options);

// Vertex count of makeProceduralArm(options).
inline std::size_t armVertexCount(const ArmOptions& o) { return static_cast<std::size_t>(o.rings) * o.ring_vertices; }

}  // namespace odeskin
