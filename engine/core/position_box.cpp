// SPDX-License-Identifier: MIT
#include "position_box.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace odeskin {

Result<PositionBox> checkedPositionBox(std::span<const Vec3> positions, const std::string& who,
                                       std::size_t first_number) {
  if (positions.empty()) return PositionBox{};
  const std::string prefix = who.empty() ? who : who + ": ";
  Vec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < positions.size(); ++i) {
    const Vec3& p = positions[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
      return invalidArgument(prefix + "vertex " + std::to_string(first_number + i) + " is not finite");
    }
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  // A path's length is a sum of at most V edges, none longer than the diagonal; the diagonal is
  // itself a square root of a sum of squares, so its being finite bounds every squared length.
  const double diagonal = glm::length(hi - lo);
  if (!std::isfinite(diagonal * static_cast<double>(positions.size()))) {
    const Vec3 extent = hi - lo;
    char span[32];
    std::snprintf(span, sizeof span, "%g", std::max({extent.x, extent.y, extent.z}));
    return invalidArgument(prefix + "the mesh is too large for double-precision distances (its bounding box spans " + span +
                           "); scale it down");
  }
  return PositionBox{lo, hi, diagonal};
}

}  // namespace odeskin
