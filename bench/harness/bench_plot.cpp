// SPDX-License-Identifier: MIT
#include "bench_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "engine/visual/compose.hpp"
#include "engine/visual/png_writer.hpp"
#include "engine/visual/text.hpp"

namespace odeskin::bench {
namespace {

using visual::Image;
using visual::Rgba8;

constexpr int kWidth = 960, kHeight = 600;
constexpr int kLeft = 90, kRight = 260, kTop = 50, kBottom = 60;  // plot margins; the legend sits right

// A colour per series (twelve before any repeats: 3 kernels x 4 backends) and a dash per case.
Rgba8 seriesColour(std::size_t index) {
  static const Rgba8 palette[] = {{31, 119, 180, 255}, {214, 39, 40, 255},  {44, 160, 44, 255},
                                  {148, 103, 189, 255}, {255, 127, 14, 255}, {23, 190, 207, 255},
                                  {140, 86, 75, 255},  {127, 127, 127, 255}, {188, 189, 34, 255},
                                  {0, 0, 0, 255},      {227, 119, 194, 255}, {0, 90, 50, 255}};
  return palette[index % std::size(palette)];
}

void plotPixel(Image& image, long x, long y, Rgba8 colour) {
  if (x >= 0 && y >= 0 && x < static_cast<long>(image.width) && y < static_cast<long>(image.height)) {
    image.at(static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(y)) = colour;
  }
}

// A thick line; `dash` > 0 leaves gaps of that many pixels.
void drawLine(Image& image, double x0, double y0, double x1, double y1, Rgba8 colour, int dash) {
  const double length = std::hypot(x1 - x0, y1 - y0);
  const int steps = std::max(1, static_cast<int>(length));
  for (int i = 0; i <= steps; ++i) {
    if (dash > 0 && (i / dash) % 2 == 1) continue;
    const double t = static_cast<double>(i) / steps;
    const long x = std::lround(x0 + t * (x1 - x0)), y = std::lround(y0 + t * (y1 - y0));
    for (long dy = -1; dy <= 1; ++dy)
      for (long dx = -1; dx <= 1; ++dx) plotPixel(image, x + dx, y + dy, colour);
  }
}

// "1e6": snprintf rather than string concatenation, which GCC 12 misreads under -Wrestrict.
std::string decadeLabel(double exponent) {
  char text[16];
  std::snprintf(text, sizeof text, "1e%d", static_cast<int>(exponent));
  return text;
}

struct Series {
  std::string label;
  int dash = 0;
  std::vector<std::pair<double, double>> points;  // (vertices, vertices per second)
};

}  // namespace

Status writePlot(const std::filesystem::path& path, const BenchReport& report, int terms) {
  int n_plot = 0;
  for (const BenchRecord& r : report.records) {
    if (r.kernel == "odeskin" && r.terms <= terms) n_plot = std::max(n_plot, r.terms);
  }
  std::map<std::string, Series> series;
  for (const BenchRecord& r : report.records) {
    if (r.seconds_per_frame <= 0.0 || (r.kernel == "odeskin" && r.terms != n_plot)) continue;
    char threads_text[16] = "";
    if (r.backend != "vulkan") std::snprintf(threads_text, sizeof threads_text, " %ut", r.threads);
    char label_text[96];
    if (r.kernel == "odeskin") {
      std::snprintf(label_text, sizeof label_text, "odeskin N=%d %s%s", r.terms, r.backend.c_str(), threads_text);
    } else {
      std::snprintf(label_text, sizeof label_text, "%s %s%s", r.kernel.c_str(), r.backend.c_str(), threads_text);
    }
    const std::string label = label_text;
    Series& s = series[label];
    s.label = label;
    s.dash = r.kernel == "odeskin" ? 0 : (r.kernel == "lbs" ? 6 : 2);
    s.points.emplace_back(static_cast<double>(r.vertices), r.verticesPerSecond());
  }
  if (series.empty()) return invalidArgument("bench plot: no records to plot");
  double x_lo = INFINITY, x_hi = -INFINITY, y_lo = INFINITY, y_hi = -INFINITY;
  for (auto& [label, s] : series) {
    std::sort(s.points.begin(), s.points.end());
    for (const auto& [x, y] : s.points) {
      x_lo = std::min(x_lo, std::log10(x));
      x_hi = std::max(x_hi, std::log10(x));
      y_lo = std::min(y_lo, std::log10(y));
      y_hi = std::max(y_hi, std::log10(y));
    }
  }
  x_lo = std::floor(x_lo), x_hi = std::max(std::ceil(x_hi), x_lo + 1.0);
  y_lo = std::floor(y_lo), y_hi = std::max(std::ceil(y_hi), y_lo + 1.0);
  Image image(kWidth, kHeight, Rgba8{255, 255, 255, 255});
  const double pw = kWidth - kLeft - kRight, ph = kHeight - kTop - kBottom;
  auto px = [&](double v) { return kLeft + (std::log10(v) - x_lo) / (x_hi - x_lo) * pw; };
  auto py = [&](double v) { return kTop + ph - (std::log10(v) - y_lo) / (y_hi - y_lo) * ph; };
  const Rgba8 grid{220, 220, 220, 255}, ink{40, 40, 40, 255};
  for (double d = x_lo; d <= x_hi + 1e-9; d += 1.0) {
    const double x = kLeft + (d - x_lo) / (x_hi - x_lo) * pw;
    visual::fillRect(image, std::lround(x), kTop, 1, static_cast<std::int64_t>(ph), grid);
    visual::drawText(image, std::lround(x) - 12, kTop + static_cast<std::int64_t>(ph) + 10,
                     decadeLabel(d), ink, 2);
  }
  for (double d = y_lo; d <= y_hi + 1e-9; d += 1.0) {
    const double y = kTop + ph - (d - y_lo) / (y_hi - y_lo) * ph;
    visual::fillRect(image, kLeft, std::lround(y), static_cast<std::int64_t>(pw), 1, grid);
    visual::drawText(image, 20, std::lround(y) - 6, decadeLabel(d), ink, 2);
  }
  visual::fillRect(image, kLeft, kTop, 1, static_cast<std::int64_t>(ph), ink);
  visual::fillRect(image, kLeft, kTop + static_cast<std::int64_t>(ph), static_cast<std::int64_t>(pw), 1, ink);
  std::string title = "vertices per second vs vertices (log-log); ";
  title += report.device;
  visual::drawText(image, kLeft, 16, title, ink, 2);
  visual::drawText(image, kLeft + static_cast<std::int64_t>(pw) / 2 - 40, kHeight - 24, "vertices", ink, 2);
  std::size_t index = 0;
  std::int64_t legend_y = kTop;
  for (const auto& [label, s] : series) {
    const Rgba8 colour = seriesColour(index++);
    for (std::size_t i = 0; i + 1 < s.points.size(); ++i) {
      drawLine(image, px(s.points[i].first), py(s.points[i].second), px(s.points[i + 1].first),
               py(s.points[i + 1].second), colour, s.dash);
    }
    for (const auto& [x, y] : s.points) visual::fillRect(image, std::lround(px(x)) - 3, std::lround(py(y)) - 3, 7, 7, colour);
    const double legend_line_y = static_cast<double>(legend_y + 6);
    drawLine(image, kWidth - kRight + 15, legend_line_y, kWidth - kRight + 45, legend_line_y, colour, s.dash);
    visual::drawText(image, kWidth - kRight + 52, legend_y, s.label, ink, 1);
    legend_y += 18;
  }
  return visual::writePng(path, image);
}

}  // namespace odeskin::bench
