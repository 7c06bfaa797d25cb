// SPDX-License-Identifier: MIT
// The iso-parametric curves of a mesh and every vertex's binding to them (PIPELINE.md 3).
#pragma once

#include <cstdint>
#include <vector>

#include "../core/iso_curve.hpp"
#include "../core/status.hpp"
#include "../core/types.hpp"

namespace odeskin {

struct CurveSet {
  std::vector<IsoCurve> curves;              // C
  std::vector<CurveBinding> bindings;        // V: every vertex, none left unbound
  std::vector<std::uint32_t> vertex_parts;   // V: the body part (bone) each vertex belongs to
};

// kInvalidArgument naming the first offender: a binding for a curve that does not exist, w outside
// [0, 1], v outside [0, 1], a curve with fewer than 3 points, a point index >= vertex_count or t
// outside [0, 1], v not non-decreasing along a curve or sized unlike its points.
Status validateCurveSet(const CurveSet& set, std::size_t vertex_count);

}  // namespace odeskin
