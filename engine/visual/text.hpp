// SPDX-License-Identifier: MIT
// Labels on pictures (tick values, panel names) drawn with stb_easy_font, Sean Barrett's
// public-domain ASCII font built from rectangles (Debian libstb-dev), scaled by whole pixels so
// strokes stay crisp.
#pragma once

#include <cstdint>
#include <string_view>

#include "image.hpp"

namespace odeskin::visual {

struct TextSize {
  std::int64_t width = 0;
  std::int64_t height = 0;  // of a capital letter, without descenders
};

// Printable ASCII only; other bytes are drawn as '?'. `scale` >= 1 pixels per font unit.
TextSize textSize(std::string_view text, int scale);

// Draws `text` with the top left of its first capital at (x, y); clipped to the image.
void drawText(Image& image, std::int64_t x, std::int64_t y, std::string_view text, Rgba8 colour, int scale);

}  // namespace odeskin::visual
