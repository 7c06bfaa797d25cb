// SPDX-License-Identifier: MIT
// A unit vector from any finite one, however long or short.
#pragma once

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "types.hpp"

namespace odeskin {

// v / |v|, divided by its largest component first: the squared length of a vector 1e-200 long
// underflows to 0, and of one 1e200 long overflows. (0, 0, 0) for the zero vector.
inline Vec3 unitVector(const Vec3& v) {
  const double largest = std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)});
  return largest > 0.0 ? glm::normalize(v / largest) : Vec3(0.0);
}

}  // namespace odeskin
