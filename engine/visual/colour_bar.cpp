// SPDX-License-Identifier: MIT
#include "colour_bar.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include "compose.hpp"
#include "render_shading.h"
#include "text.hpp"

namespace odeskin::visual {
namespace {

constexpr double kPercent = 100.0;

}  // namespace

std::vector<double> niceTicks(double max, int target) {
  if (!(max > 0.0 && std::isfinite(max))) return {};
  const double raw = max / std::max(target, 1);
  const double decade = std::pow(10.0, std::floor(std::log10(raw)));
  double step = 10.0 * decade;
  for (double m : {1.0, 2.0, 2.5, 5.0}) {
    if (m * decade >= raw) {
      step = m * decade;
      break;
    }
  }
  std::vector<double> ticks;
  // A tick within 1e-9 of max counts as on the bar (max itself is often a round number).
  for (int i = 0; i * step <= max * (1.0 + 1e-9); ++i) ticks.push_back(i * step);
  return ticks;
}

std::string tickLabel(double value, double step) {
  char text[32];
  if (value == 0.0) return "0";
  if (step < 1e-3 || std::abs(value) >= 1e5) {
    std::snprintf(text, sizeof text, "%.3g", value);
    return text;
  }
  // Decimals enough for the step: 0.25 needs 2, 0.5 needs 1, 2 needs 0.
  int decimals = 0;
  while (decimals < 6 && std::abs(step * std::pow(10.0, decimals) - std::round(step * std::pow(10.0, decimals))) > 1e-6) {
    ++decimals;
  }
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

std::int64_t colourBarTitleHeight(const ColourBarStyle& style) {
  const std::int64_t gap = std::int64_t{2} * style.text_scale;
  const std::int64_t line = textSize("0", style.text_scale).height;
  return line / 2 + 4 * gap + 2 * line;
}

std::int64_t colourBarWidth(double heat_max, const ColourBarStyle& style) {
  const std::vector<double> ticks = niceTicks(heat_max * kPercent, 5);
  const double step = ticks.size() > 1 ? ticks[1] : heat_max * kPercent;
  std::int64_t label = 0;
  for (double t : ticks) label = std::max(label, textSize(tickLabel(t, step), style.text_scale).width);
  char top[32];
  std::snprintf(top, sizeof top, "%.3g", heat_max * kPercent);
  label = std::max(label, textSize(top, style.text_scale).width);
  const std::int64_t gap = std::int64_t{2} * style.text_scale;
  const std::int64_t body = style.bar_width + style.tick_length + gap + label;
  const std::int64_t title =
      std::max(textSize(style.title, style.text_scale).width, textSize(style.unit, style.text_scale).width);
  return std::max(body, title) + 4 * gap;  // a margin each side; more on the right, at the edge
}

void drawColourBar(Image& image, std::int64_t x, std::int64_t top, std::int64_t bottom, double heat_max,
                   const ColourBarStyle& style) {
  const std::int64_t gap = std::int64_t{2} * style.text_scale;
  const std::int64_t line = textSize("0", style.text_scale).height;
  const std::int64_t bar_x = x + gap;
  const std::int64_t height = std::max<std::int64_t>(bottom - top, 1);

  // Title: two lines above the bar, clear of the top tick's label (which is centred on `top`).
  const std::int64_t unit_y = top - line / 2 - 2 * gap - line;
  drawText(image, x + gap, unit_y - 2 * gap - line, style.title, style.ink, style.text_scale);
  drawText(image, x + gap, unit_y, style.unit, style.ink, style.text_scale);

  for (std::int64_t r = top; r < top + height; ++r) {
    const float s = static_cast<float>((double(top + height - r) - 0.5) / double(height));
    fillRect(image, bar_x, r, style.bar_width, 1, toRgba8(shader::heatColour(s)));
  }
  // A thin outline separates light colours (yellow) from a light background.
  fillRect(image, bar_x - 1, top - 1, style.bar_width + 2, 1, style.ink);
  fillRect(image, bar_x - 1, top + height, style.bar_width + 2, 1, style.ink);
  fillRect(image, bar_x - 1, top, 1, height, style.ink);
  fillRect(image, bar_x + style.bar_width, top, 1, height, style.ink);

  const std::vector<double> ticks = niceTicks(heat_max * kPercent, 5);
  const double step = ticks.size() > 1 ? ticks[1] : heat_max * kPercent;
  // The top of the bar is labelled too when the last round tick sits well below it, so the scale's
  // end is always readable.
  std::vector<std::pair<double, std::string>> labels;
  labels.reserve(ticks.size() + 1);
  for (double t : ticks) labels.emplace_back(t, tickLabel(t, step));
  const double top_value = heat_max * kPercent;
  if (!ticks.empty() && ticks.back() < 0.9 * top_value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", top_value);
    labels.emplace_back(top_value, text);
  }
  for (const auto& [t, label] : labels) {
    const std::int64_t row = top + height - std::llround(t / (heat_max * kPercent) * double(height));
    const std::int64_t y = std::clamp<std::int64_t>(row, top, top + height - 1);
    fillRect(image, bar_x + style.bar_width, y, style.tick_length, std::max(1, style.text_scale / 2), style.ink);
    drawText(image, bar_x + style.bar_width + style.tick_length + gap, y - line / 2, label, style.ink, style.text_scale);
  }
}

}  // namespace odeskin::visual
