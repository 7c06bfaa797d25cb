// SPDX-License-Identifier: MIT
#include "text.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <stb_easy_font.h>

#include "compose.hpp"

namespace odeskin::visual {
namespace {

constexpr std::int64_t kCapitalHeight = 7;  // font units from the top of a capital to the baseline

std::string printable(std::string_view text) {
  std::string out(text);
  for (char& c : out) {
    if (c < 32 || c > 126) c = '?';
  }
  return out;
}

// stb_easy_font's vertex record: x, y, z, then RGBA bytes.
struct FontVertex {
  float x;
  float y;
  float z;
  unsigned char colour[4];
};

}  // namespace

TextSize textSize(std::string_view text, int scale) {
  std::string copy = printable(text);
  return {static_cast<std::int64_t>(stb_easy_font_width(copy.data())) * scale, kCapitalHeight * scale};
}

void drawText(Image& image, std::int64_t x, std::int64_t y, std::string_view text, Rgba8 colour, int scale) {
  std::string copy = printable(text);
  // About 270 bytes per character (the header's estimate); four vertices per quad.
  std::vector<FontVertex> vertices(copy.size() * 24 + 4);
  const int quads = stb_easy_font_print(0.0f, 0.0f, copy.data(), nullptr, vertices.data(),
                                        static_cast<int>(vertices.size() * sizeof(FontVertex)));
  for (int q = 0; q < quads; ++q) {
    const FontVertex* v = &vertices[static_cast<std::size_t>(q) * 4];
    // cppcheck-suppress duplicateAssignExpression ; the box starts at the first corner, min and max alike
    float x0 = v[0].x, x1 = v[0].x, y0 = v[0].y, y1 = v[0].y;
    for (int k = 1; k < 4; ++k) {
      x0 = std::min(x0, v[k].x);
      x1 = std::max(x1, v[k].x);
      y0 = std::min(y0, v[k].y);
      y1 = std::max(y1, v[k].y);
    }
    // Capitals span font units [0, 7) below the origin; descenders reach 9.
    const std::int64_t px = x + std::llround(x0 * static_cast<float>(scale));
    const std::int64_t py = y + std::llround(y0 * static_cast<float>(scale));
    fillRect(image, px, py, std::llround((x1 - x0) * static_cast<float>(scale)),
             std::llround((y1 - y0) * static_cast<float>(scale)), colour);
  }
}

}  // namespace odeskin::visual
