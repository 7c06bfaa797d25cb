// SPDX-License-Identifier: MIT
// The "weights" animation of the compact export: every target's weight curve as CUBICSPLINE keys
// with the analytic derivatives as tangents (glTF 2.0 appendix C), or as LINEAR keys
// (key_interpolation.hpp), keys shared by all targets (the channel has one sampler). Weights are
// kept in [0, 1] (Blender clamps negative shape-key values, ECOSYSTEM.md 2.3): a field whose curve
// g goes negative is split into a "+" target with weight max(g, 0) / scale and a "-" target with
// weight max(-g, 0) / scale, each displacement multiplied by its sign and scale = max of its part
// over the segment. Keys sit at both ends of every segment and at every zero crossing of every
// curve (where max(g, 0) has a kink: CUBICSPLINE keys have separate in- and out-tangents; a LINEAR
// key's kink is free), and intervals are halved until the interpolant matches every weight.
#pragma once

#include <cstdint>
#include <vector>

#include "../core/result.hpp"
#include "key_interpolation.hpp"
#include "mode_targets.hpp"

namespace odeskin {

struct SplitTarget {
  std::size_t source = 0;  // index into ModeTargetSet::targets
  int sign = 1;            // +1 or -1: this target carries max(sign * g, 0)
  double scale = 1.0;      // its maximum over the segment; displacement = sign * scale * field
};

struct WeightKeyOptions {
  // Position error allowed from interpolating the weights (absolute, same unit as the mesh); within
  // a segment it is shared out equally among the segment's targets, so their sum stays below it.
  double position_tolerance = 1e-5;
  // Every weight also follows its curve within this (in weight units), so a curve editor shows the
  // time basis even where a target moves the mesh too little for the position tolerance to matter.
  double weight_tolerance = 1e-4;
  double min_key_gap = 1e-5;  // in t: intervals are not halved below this (float32 times stay increasing)
  KeyInterpolation interpolation = KeyInterpolation::kCubicSpline;
};

struct WeightKeys {
  std::vector<SplitTarget> targets;
  KeyInterpolation interpolation = KeyInterpolation::kCubicSpline;
  std::vector<double> times;  // global t of every key (0 .. segment count), strictly increasing
  // keys x targets, key-major: each target's in-tangent, value and out-tangent (tangents are d/dt;
  // LINEAR keys leave them unused).
  std::vector<double> in_tangents;
  std::vector<double> values;
  std::vector<double> out_tangents;
  double max_weight_error = 0.0;    // max |interpolated - exact| of any target's weight (dense check)
  double max_position_error = 0.0;  // max over segments of sum_j weight error_j * max |displacement_j|
  std::size_t weightCount() const { return targets.size(); }
};

// kInvalidArgument for a non-positive tolerance or gap, or a target whose curve is not finite.
Result<WeightKeys> placeWeightKeys(const ModeTargetSet& set, std::uint32_t segment_count, const WeightKeyOptions& options);

// glTF 2.0's cubic Hermite spline on one interval: v0, v1 the values, d0 the out-tangent of the
// first key, d1 the in-tangent of the second (per unit of the interval's parameter), h its length
// and s in [0, 1] the position inside it.
inline double cubicHermite(double v0, double d0, double v1, double d1, double h, double s) {
  const double s2 = s * s, s3 = s2 * s;
  return (2.0 * s3 - 3.0 * s2 + 1.0) * v0 + h * (s3 - 2.0 * s2 + s) * d0 + (-2.0 * s3 + 3.0 * s2) * v1 +
         h * (s3 - s2) * d1;
}

}  // namespace odeskin
