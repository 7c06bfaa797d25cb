// SPDX-License-Identifier: MIT
// A double as float32 stores it, for tests that compare with what a float file or buffer holds.
// The rounding goes through a volatile float: GCC 12.2's vectorizers, at -O2 and above, drop it
// from `Vec3(static_cast<float>(p.x), ...)` (the SLP vectorizer) and from `p = Vec3(glm::vec3(p))`
// over a vector of Vec3 (the loop vectorizer), and give the doubles back unchanged.
#pragma once

#include "engine/core/types.hpp"

namespace odeskin::testing {

inline double roundedToFloat(double x) {
  const volatile float rounded = static_cast<float>(x);
  return rounded;
}

inline Vec3 roundedToFloat(const Vec3& p) { return {roundedToFloat(p.x), roundedToFloat(p.y), roundedToFloat(p.z)}; }

}  // namespace odeskin::testing
