// SPDX-License-Identifier: MIT
// The range of the float32 layouts: the packed deform data (the fast CPU path, the runtime and the
// GPU) and glTF's positions: one bound for both.
#pragma once

#include <cmath>
#include <cstddef>
#include <span>

#include "types.hpp"

namespace odeskin {

// Float's range is 3.4e38; 1e38 leaves room for sums of a few such values (a morph target's
// difference of two positions, the terms of a deformation).
inline constexpr double kFloat32CoordinateLimit = 1e38;

// The index of the first vector with a coordinate beyond kFloat32CoordinateLimit or not finite;
// values.size() when every one fits.
inline std::size_t firstBeyondFloat32(std::span<const Vec3> values) {
  for (std::size_t i = 0; i < values.size(); ++i) {
    // Each coordinate on its own: std::max drops a NaN that is not its first argument.
    const Vec3& v = values[i];
    if (!(std::abs(v.x) <= kFloat32CoordinateLimit && std::abs(v.y) <= kFloat32CoordinateLimit &&
          std::abs(v.z) <= kFloat32CoordinateLimit)) {
      return i;
    }
  }
  return values.size();
}

}  // namespace odeskin
