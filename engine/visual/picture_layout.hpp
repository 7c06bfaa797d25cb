// SPDX-License-Identifier: MIT
// How a picture is laid out: panels of one size side by side (every panel drawn with the same
// camera, so sizes compare), up to two lines of label under each, and the colour bar on the right
// when a heat map is shown. The whole picture is exactly the requested width x height.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "../core/result.hpp"
#include "colour_bar.hpp"
#include "image.hpp"

namespace odeskin::visual {

struct PictureSpec {
  std::uint32_t width = 800;        // whole picture, pixels; 0: panels x panel_width_hint + colour bar
  std::uint32_t height = 600;
  std::size_t panels = 1;           // >= 1
  std::size_t label_lines = 0;      // 0, 1 or 2 lines of text under every panel
  std::optional<double> heat_max;   // set: draw the colour bar for errors in [0, heat_max]
  std::uint32_t panel_width_hint = 720;  // panel width when width is 0
};

struct PictureLayout {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::uint32_t panel_width = 0;        // every panel's rendered size
  std::uint32_t panel_height = 0;
  std::vector<std::int64_t> panel_left; // x of each panel's left edge; panels start at y = 0
  std::int64_t label_top = 0;           // y of the first label line
  std::size_t label_lines = 0;
  int text_scale = 1;                   // pixels per font unit, from the picture height
  std::optional<double> heat_max;
  std::int64_t bar_left = 0;            // colour bar column (heat_max set)
  std::int64_t bar_top = 0;
  std::int64_t bar_bottom = 0;
  ColourBarStyle bar_style;
};

// kInvalidArgument: no panels, more than 2 label lines, a non-positive or non-finite heat_max, or
// a picture too small for its parts (panels under 16 x 16 pixels; the message gives the sizes).
Result<PictureLayout> layoutPicture(const PictureSpec& spec);

// Puts the rendered panels (premultiplied, layout.panel_width x panel_height each, as the
// renderer returns them) over `background`, writes each panel's label lines centred under it, and
// draws the colour bar. labels[i] holds panel i's lines (fewer than label_lines is fine).
// Preconditions: panels.size() == layout.panel_left.size(), labels empty or the same size.
Image composePicture(const PictureLayout& layout, std::span<const Image> panels,
                     std::span<const std::vector<std::string>> labels, Rgba8 background, Rgba8 ink);

}  // namespace odeskin::visual
