// SPDX-License-Identifier: MIT
// The colour bar beside a heat map (as the thesis's Fig. 6.15): the error colour map from 0 at the
// bottom to heat_max at the top, with ticks at round values labelled in percent of the reference's
// bounding-box diagonal.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "image.hpp"

namespace odeskin::visual {

// Round tick values 0, step, 2 step, ... <= max, step one of 1, 2, 2.5, 5 x 10^k chosen to give
// about `target` intervals (at least 1). Empty when max is not positive and finite.
std::vector<double> niceTicks(double max, int target);

// A tick value as text, with as many decimals as `step` needs ("0", "0.25", "1.5", "2e-05").
std::string tickLabel(double value, double step);

struct ColourBarStyle {
  int text_scale = 2;             // pixels per font unit
  std::int64_t bar_width = 22;    // pixels
  std::int64_t tick_length = 6;   // pixels
  Rgba8 ink{40, 40, 46, 255};     // ticks, labels, outline
  std::string title = "error";    // first title line
  std::string unit = "% of diag";  // second title line (values are shown as percent)
};

// Rows above the bar that its two title lines take.
std::int64_t colourBarTitleHeight(const ColourBarStyle& style);

// Width in pixels that drawColourBar needs for `heat_max` (title, bar, ticks and labels).
std::int64_t colourBarWidth(double heat_max, const ColourBarStyle& style);

// Draws the bar in the column [x, x + colourBarWidth) of `image`, the bar itself spanning rows
// [top, bottom) with the title above it (colourBarTitleHeight rows). Row r of the bar has heatColour(s) with s = (bottom - r -
// 0.5) / (bottom - top), unlit. Labels are heat values x 100 (percent): the round ticks, and the
// top value itself when the last tick is below 90% of it. Precondition: heat_max > 0.
void drawColourBar(Image& image, std::int64_t x, std::int64_t top, std::int64_t bottom, double heat_max,
                   const ColourBarStyle& style);

}  // namespace odeskin::visual
