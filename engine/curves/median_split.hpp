// SPDX-License-Identifier: MIT
// The one split behind the curve stage's spatial trees (plane cuts' triangle boxes, vertex
// binding's clusters): reorder indices [first, last) so that the half with the smaller coordinate
// along the points' widest spread comes first, and return where the halves meet.
#pragma once

#include <algorithm>
#include <cstdint>
#include <limits>
#include <span>

#include <glm/common.hpp>

#include "../core/types.hpp"

namespace odeskin {

// `points[order[k]]` is the point of entry k. Precondition: first < last <= order.size().
inline std::uint32_t splitAtMedian(std::span<std::uint32_t> order, std::span<const Vec3> points, std::uint32_t first,
                                   std::uint32_t last) {
  Vec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for (std::uint32_t k = first; k < last; ++k) {
    lo = glm::min(lo, points[order[k]]);
    hi = glm::max(hi, points[order[k]]);
  }
  const Vec3 spread = hi - lo;
  const int axis = spread.x >= spread.y && spread.x >= spread.z ? 0 : (spread.y >= spread.z ? 1 : 2);
  const std::uint32_t middle = first + (last - first) / 2;
  std::nth_element(order.begin() + first, order.begin() + middle, order.begin() + last,
                   [&](std::uint32_t a, std::uint32_t b) { return points[a][axis] < points[b][axis]; });
  return middle;
}

}  // namespace odeskin
