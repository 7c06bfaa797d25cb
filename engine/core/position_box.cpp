// SPDX-License-Identifier: MIT
#include "position_box.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "finite_vector.hpp"

namespace odeskin {

Result<PositionBox> checkedPositionBox(std::span<const Vec3> positions, const std::string& who,
                                       std::size_t first_number) {
  if (positions.empty()) return PositionBox{};
  const std::string prefix = who.empty() ? who : who + ": ";
  Vec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < positions.size(); ++i) {
    const Vec3& p = positions[i];
    if (!isFinite(p)) {
      return invalidArgument(prefix + "vertex " + std::to_string(first_number + i) + " is not finite");
    }
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  const Vec3 extent = hi - lo;
  const double side = std::max({extent.x, extent.y, extent.z});
  auto refused = [&](const char* size, const char* advice) {
    char span[32];
    std::snprintf(span, sizeof span, "%g", side);
    return invalidArgument(prefix + "the mesh is too " + size + " for double-precision distances (its bounding box spans " +
                           span + "); scale it " + advice);
  };
  // A path's length is a sum of at most V edges, none longer than the diagonal; the diagonal is
  // itself a square root of a sum of squares, so its being finite bounds every squared length.
  const double diagonal = glm::length(extent);
  if (!std::isfinite(diagonal * static_cast<double>(positions.size()))) return refused("large", "down");
  // The other end: squares below double's normal range lose their digits (a cat 1e-160 across got
  // 48 joints from the curve rig where it gets 31 at any size above 1e-100; at 1e-200 its edges
  // all measured 0). A box 1e-100 across leaves edges down to 1e-50 of it their full precision. The
  // longest side, not the diagonal, whose square may itself underflow. All at one point is the
  // caller's case.
  if (side > 0.0 && side < kMinPositionBoxSpan) return refused("small", "up");
  // Centroids sum up to V coordinates: a horse 1 across at 1e308 from the origin overflowed them,
  // and the curve rig's centre search then followed NaN distances until memory ran out.
  const double reach = std::max({-lo.x, -lo.y, -lo.z, hi.x, hi.y, hi.z});
  if (!std::isfinite(reach * static_cast<double>(positions.size()))) {
    char far[32];
    std::snprintf(far, sizeof far, "%g", reach);
    return invalidArgument(prefix + "the mesh lies too far from the origin for double-precision sums (coordinates up to " +
                           far + "); move it towards the origin");
  }
  return PositionBox{lo, hi, diagonal};
}

}  // namespace odeskin
