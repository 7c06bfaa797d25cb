// SPDX-License-Identifier: MIT
#include "picture_layout.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "compose.hpp"
#include "png_writer.hpp"
#include "text.hpp"

namespace odeskin::visual {
namespace {

constexpr std::uint32_t kMinPanel = 16;

// Label line pitch in font units: capital height 7 plus 4 of leading.
constexpr std::int64_t kLinePitch = 11;

}  // namespace

Result<PictureLayout> layoutPicture(const PictureSpec& spec) {
  if (spec.panels == 0) return invalidArgument("picture: nothing to draw (no panels)");
  if (spec.label_lines > 2) return invalidArgument("picture: at most 2 label lines");
  if (spec.heat_max && !(*spec.heat_max > 0.0 && std::isfinite(*spec.heat_max))) {
    return invalidArgument("picture: the heat scale must be a positive number");
  }
  PictureLayout layout;
  layout.height = spec.height;
  layout.label_lines = spec.label_lines;
  layout.heat_max = spec.heat_max;
  // Labels about 3% of the height tall: scale 1 below 375 pixels, 2 up to 625, 3 up to 875.
  layout.text_scale = static_cast<int>(std::clamp<std::int64_t>(std::lround(spec.height / 250.0), 1, 4));
  layout.bar_style.text_scale = layout.text_scale;
  layout.bar_style.bar_width = std::int64_t{11} * layout.text_scale;
  layout.bar_style.tick_length = std::int64_t{3} * layout.text_scale;

  std::int64_t label_height = 0;
  if (spec.label_lines != 0) {
    label_height = (static_cast<std::int64_t>(spec.label_lines) * kLinePitch + 4) * layout.text_scale;
  }
  const std::int64_t bar_width = spec.heat_max ? colourBarWidth(*spec.heat_max, layout.bar_style) : 0;
  const std::uint64_t width = spec.width != 0 ? spec.width
                                              : std::uint64_t{spec.panels} * spec.panel_width_hint +
                                                    static_cast<std::uint64_t>(bar_width);
  // Checked before any panel is drawn: 300 inputs rendered for 7 s, then failed at the PNG.
  if (width > kMaxPngSide || spec.height > kMaxPngSide) {
    return invalidArgument("picture: " + std::to_string(spec.panels) + " panel(s) make it " + std::to_string(width) +
                           " x " + std::to_string(spec.height) + " pixels, over the " + std::to_string(kMaxPngSide) +
                           " a side a PNG may have here; give a smaller size or fewer panels");
  }
  layout.width = static_cast<std::uint32_t>(width);
  const std::int64_t panels_width = std::int64_t(layout.width) - bar_width;
  const std::int64_t panel_width = panels_width / static_cast<std::int64_t>(spec.panels);
  const std::int64_t panel_height = std::int64_t(spec.height) - label_height;
  if (panel_width < kMinPanel || panel_height < kMinPanel) {
    return invalidArgument("picture: " + std::to_string(layout.width) + " x " + std::to_string(spec.height) +
                           " leaves " + std::to_string(std::max<std::int64_t>(panel_width, 0)) + " x " +
                           std::to_string(std::max<std::int64_t>(panel_height, 0)) + " pixels for each of " +
                           std::to_string(spec.panels) + " panel(s); at least 16 x 16 are needed");
  }
  layout.panel_width = static_cast<std::uint32_t>(panel_width);
  layout.panel_height = static_cast<std::uint32_t>(panel_height);
  // Columns left over by the integer division are shared out as a margin on both sides.
  const std::int64_t spare = panels_width - panel_width * static_cast<std::int64_t>(spec.panels);
  for (std::size_t i = 0; i < spec.panels; ++i) layout.panel_left.push_back(spare / 2 + static_cast<std::int64_t>(i) * panel_width);
  layout.label_top = panel_height + 2 * static_cast<std::int64_t>(layout.text_scale);
  if (spec.heat_max) {
    layout.bar_left = panels_width;
    // Room above the bar for its two title lines, and a shorter bar than the panel, as in a figure.
    const std::int64_t title = colourBarTitleHeight(layout.bar_style);
    layout.bar_top = std::max<std::int64_t>(title + std::int64_t{2} * layout.text_scale, std::llround(0.16 * double(panel_height)));
    layout.bar_bottom = std::max<std::int64_t>(layout.bar_top + 8, std::llround(0.88 * double(panel_height)));
  }
  return layout;
}

Image composePicture(const PictureLayout& layout, std::span<const Image> panels,
                     std::span<const std::vector<std::string>> labels, Rgba8 background, Rgba8 ink) {
  Image picture(layout.width, layout.height, background);
  for (std::size_t i = 0; i < panels.size() && i < layout.panel_left.size(); ++i) {
    blit(picture, overBackground(panels[i], background), layout.panel_left[i], 0);
    if (i >= labels.size()) continue;
    for (std::size_t line = 0; line < labels[i].size() && line < layout.label_lines; ++line) {
      const std::int64_t text_width = textSize(labels[i][line], layout.text_scale).width;
      const std::int64_t x = layout.panel_left[i] + (std::int64_t(layout.panel_width) - text_width) / 2;
      const std::int64_t y = layout.label_top + static_cast<std::int64_t>(line) * kLinePitch * layout.text_scale;
      drawText(picture, x, y, labels[i][line], ink, layout.text_scale);
    }
  }
  if (layout.heat_max) {
    ColourBarStyle style = layout.bar_style;
    style.ink = ink;
    drawColourBar(picture, layout.bar_left, layout.bar_top, layout.bar_bottom, *layout.heat_max, style);
  }
  return picture;
}

}  // namespace odeskin::visual
