// SPDX-License-Identifier: MIT
// Iso-parametric curves as line segments for drawing (the thesis's Fig. 6.7). Curve points lie on
// edges of the bind mesh (CurvePoint {a, b, t}), so a curve on a deformed mesh is the same lerp of
// the deformed edge ends: no re-cutting per frame.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "../core/iso_curve.hpp"
#include "../core/result.hpp"

namespace odeskin::visual {

struct CurveSegments {
  std::vector<Vec3> endpoints;                 // 2 per segment
  std::vector<std::uint32_t> curve_of_segment;  // 1 per segment: index into the curves
  std::vector<std::uint32_t> part_of_segment;   // 1 per segment: the curve's body part (IsoCurve::part)
};

// Consecutive points of every curve, plus last -> first for closed curves. kInvalidArgument naming
// the curve and point when a vertex index is out of range of `positions`.
Result<CurveSegments> curveSegments(std::span<const IsoCurve> curves, std::span<const Vec3> positions);

// A colour per curve or part index, cycling through a palette of curvePaletteSize() colours that
// read on the clay surface and on white.
glm::vec3 curveColour(std::uint32_t index);
std::uint32_t curvePaletteSize();

}  // namespace odeskin::visual
