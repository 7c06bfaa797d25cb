// SPDX-License-Identifier: MIT
#include "image.hpp"

#include <algorithm>
#include <cmath>

namespace odeskin::visual {

Rgba8 toRgba8(const glm::vec3& colour, float alpha) {
  // In double: 255 x is then exact enough that a float just below .5 rounds down, as the GPU's
  // UNORM conversion does (0.9f -> 229, where a float product would round up to 229.5 -> 230).
  auto byte = [](float x) { return static_cast<std::uint8_t>(std::lround(255.0 * double(std::clamp(x, 0.0f, 1.0f)))); };
  return {byte(colour.r), byte(colour.g), byte(colour.b), byte(alpha)};
}

glm::vec3 toVec3(Rgba8 c) { return glm::vec3(c.r, c.g, c.b) / 255.0f; }

}  // namespace odeskin::visual
