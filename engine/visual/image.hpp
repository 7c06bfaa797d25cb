// SPDX-License-Identifier: MIT
// An 8-bit RGBA picture in memory, rows top to bottom, what the renderer reads back and PNG files
// hold. Colours from the shaders are linear values written as UNORM bytes, with no sRGB curve, so
// a byte is round(255 x) of the CPU reference colour x.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace odeskin::visual {

struct Rgba8 {
  std::uint8_t r = 0;
  std::uint8_t g = 0;
  std::uint8_t b = 0;
  std::uint8_t a = 0;
  bool operator==(const Rgba8&) const = default;
};

// round(255 x) of each channel clamped to [0, 1] (what a UNORM attachment stores for x).
Rgba8 toRgba8(const glm::vec3& colour, float alpha = 1.0f);
glm::vec3 toVec3(Rgba8 colour);  // channel / 255

struct Image {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::vector<Rgba8> pixels;  // width x height, row-major from the top left

  Image() = default;
  Image(std::uint32_t w, std::uint32_t h, Rgba8 fill = {}) : width(w), height(h), pixels(std::size_t(w) * h, fill) {}

  // Preconditions: x < width, y < height.
  Rgba8& at(std::uint32_t x, std::uint32_t y) { return pixels[std::size_t(y) * width + x]; }
  const Rgba8& at(std::uint32_t x, std::uint32_t y) const { return pixels[std::size_t(y) * width + x]; }
  bool empty() const { return pixels.empty(); }
};

static_assert(sizeof(Rgba8) == 4, "pixels are copied as bytes to and from the GPU and PNG");

}  // namespace odeskin::visual
