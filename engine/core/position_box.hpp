// SPDX-License-Identifier: MIT
// The check a geometry stage makes of a mesh's positions before it measures lengths on them: every
// coordinate finite, and the mesh small enough that a squared length, and a sum of as many edge
// lengths as there are vertices, stay finite in double precision. A mesh 1e200 across passes a
// finiteness check, but its squared edge lengths overflow: the curve rig's distance sweeps then read
// every vertex as unreached, and the plane cuts of the curve identification recurse without end
// (both crashed before this check).
#pragma once

#include <span>
#include <string>

#include "result.hpp"
#include "types.hpp"

namespace odeskin {

struct PositionBox {
  Vec3 lo{0.0};
  Vec3 hi{0.0};
  double diagonal = 0.0;  // |hi - lo|
};

// Below this longest bounding-box side (and above 0) positions are refused as too small: squared
// edge lengths would fall out of double's normal range and lose their digits.
inline constexpr double kMinPositionBoxSpan = 1e-100;

// The positions' bounding box. kInvalidArgument "<who>: vertex I is not finite" for the first such
// vertex, "<who>: the mesh is too large for double-precision distances (its bounding box spans S);
// scale it down" when the diagonal times the vertex count overflows, or "<who>: the mesh is too
// small ... scale it up" for a longest side in (0, kMinPositionBoxSpan), or "<who>: the mesh lies
// too far from the origin for double-precision sums (coordinates up to R); move it towards the
// origin" when the largest |coordinate| times the vertex count overflows. No positions, or all at
// one point: a box of diagonal 0.
// An empty `who` leaves the "<who>: " out; vertices are numbered from `first_number` (1 where the
// caller's other messages number vertices as OBJ files do).
Result<PositionBox> checkedPositionBox(std::span<const Vec3> positions, const std::string& who,
                                       std::size_t first_number = 0);

}  // namespace odeskin
