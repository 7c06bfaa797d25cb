// SPDX-License-Identifier: MIT
#include "image.hpp"

#include <algorithm>
#include <cmath>

namespace odeskin::visual {

Rgba8 toRgba8(const glm::vec3& colour, float alpha) {
  auto byte = [](float x) { return static_cast<std::uint8_t>(std::lround(255.0f * std::clamp(x, 0.0f, 1.0f))); };
  return {byte(colour.r), byte(colour.g), byte(colour.b), byte(alpha)};
}

glm::vec3 toVec3(Rgba8 c) { return glm::vec3(c.r, c.g, c.b) / 255.0f; }

}  // namespace odeskin::visual
