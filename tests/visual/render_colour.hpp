// SPDX-License-Identifier: MIT
// Colour helpers for the picture tests: hue of an RGB colour, as the heat-map checks compare it.
#pragma once

#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

#include "engine/visual/image.hpp"

namespace odeskin::visual {

// HSV hue in degrees [0, 360); 0 for greys.
inline double hueDegrees(const glm::vec3& c) {
  const double r = c.r, g = c.g, b = c.b;
  const double hi = std::max({r, g, b});
  const double lo = std::min({r, g, b});
  const double chroma = hi - lo;
  if (chroma <= 0.0) return 0.0;
  double h = 0.0;
  if (hi == r) {
    h = std::fmod((g - b) / chroma + 6.0, 6.0);
  } else if (hi == g) {
    h = (b - r) / chroma + 2.0;
  } else {
    h = (r - g) / chroma + 4.0;
  }
  return 60.0 * h;
}

inline double hueDegrees(Rgba8 c) { return hueDegrees(toVec3(c)); }

// Largest channel difference.
inline int channelDistance(Rgba8 a, Rgba8 b) {
  return std::max({std::abs(a.r - b.r), std::abs(a.g - b.g), std::abs(a.b - b.b), std::abs(a.a - b.a)});
}

}  // namespace odeskin::visual
