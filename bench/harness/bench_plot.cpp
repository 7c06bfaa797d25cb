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

// Log-log axes from decade x_lo to x_hi and y_lo to y_hi (exponents), with grid and labels.
struct LogAxes {
  double x_lo = 0, x_hi = 1, y_lo = 0, y_hi = 1;
  double pw = kWidth - kLeft - kRight, ph = kHeight - kTop - kBottom;
  double px(double v) const { return kLeft + (std::log10(v) - x_lo) / (x_hi - x_lo) * pw; }
  double py(double v) const { return kTop + ph - (std::log10(v) - y_lo) / (y_hi - y_lo) * ph; }
};

void drawAxes(Image& image, const LogAxes& a, const std::string& title, const std::string& x_label,
              const std::string& y_label) {
  const Rgba8 grid{220, 220, 220, 255}, ink{40, 40, 40, 255};
  // Decades are whole exponents (the axes' ends are floors and ceilings).
  const auto decades = [](double lo, double hi) { return static_cast<int>(std::lround(hi - lo)); };
  for (int k = 0; k <= decades(a.x_lo, a.x_hi); ++k) {
    const double d = a.x_lo + k;
    const double x = kLeft + (d - a.x_lo) / (a.x_hi - a.x_lo) * a.pw;
    visual::fillRect(image, std::lround(x), kTop, 1, static_cast<std::int64_t>(a.ph), grid);
    visual::drawText(image, std::lround(x) - 12, kTop + static_cast<std::int64_t>(a.ph) + 10, decadeLabel(d), ink, 2);
  }
  for (int k = 0; k <= decades(a.y_lo, a.y_hi); ++k) {
    const double d = a.y_lo + k;
    const double y = kTop + a.ph - (d - a.y_lo) / (a.y_hi - a.y_lo) * a.ph;
    visual::fillRect(image, kLeft, std::lround(y), static_cast<std::int64_t>(a.pw), 1, grid);
    visual::drawText(image, 20, std::lround(y) - 6, decadeLabel(d), ink, 2);
  }
  visual::fillRect(image, kLeft, kTop, 1, static_cast<std::int64_t>(a.ph), ink);
  visual::fillRect(image, kLeft, kTop + static_cast<std::int64_t>(a.ph), static_cast<std::int64_t>(a.pw), 1, ink);
  visual::drawText(image, kLeft, 16, title, ink, 2);
  visual::drawText(image, kLeft + static_cast<std::int64_t>(a.pw) / 2 - 40, kHeight - 24, x_label, ink, 2);
  visual::drawText(image, 8, kTop - 22, y_label, ink, 1);
}

}  // namespace

Status writeFitPlot(const std::filesystem::path& path, const BenchReport& report) {
  std::vector<const FitStageRecord*> fits;
  for (const FitStageRecord& f : report.fit_stages) {
    if (f.dataset.find("subdivided") != std::string::npos && f.vertices > 0) fits.push_back(&f);
  }
  if (fits.empty()) return invalidArgument("bench fit plot: the report has no fits of the subdivided series");
  std::sort(fits.begin(), fits.end(), [](const FitStageRecord* a, const FitStageRecord* b) { return a->vertices < b->vertices; });
  struct StageSeries {
    const char* label;
    double (*ms)(const FitStageRecord&);
    int dash;
  };
  const StageSeries stages[] = {
      {"sum without the rig", [](const FitStageRecord& f) { return 1e3 * f.withoutRig(); }, 0},
      {"curve identification", [](const FitStageRecord& f) { return 1e3 * f.curve_identification; }, 0},
      {"geometric transform", [](const FitStageRecord& f) { return 1e3 * f.geometric_transform; }, 0},
      {"Fourier + deformation", [](const FitStageRecord& f) { return 1e3 * f.fourier_and_deformation; }, 0},
      {"analytic solve + skin", [](const FitStageRecord& f) { return 1e3 * f.analytic_solve; }, 0},
  };
  LogAxes axes;
  double x_lo = INFINITY, x_hi = -INFINITY, y_lo = std::log10(3.66), y_hi = -INFINITY;
  for (const FitStageRecord* f : fits) {
    x_lo = std::min(x_lo, std::log10(static_cast<double>(f->vertices)));
    x_hi = std::max(x_hi, std::log10(static_cast<double>(f->vertices)));
    for (const StageSeries& s : stages) {
      const double ms = s.ms(*f);
      if (!(ms > 0.0)) continue;
      y_lo = std::min(y_lo, std::log10(ms));
      y_hi = std::max(y_hi, std::log10(ms));
    }
  }
  if (!(y_hi >= y_lo)) return invalidArgument("bench fit plot: no positive stage times");
  axes.x_lo = std::floor(x_lo), axes.x_hi = std::max(std::ceil(x_hi), axes.x_lo + 1.0);
  axes.y_lo = std::floor(y_lo), axes.y_hi = std::max(std::ceil(y_hi), axes.y_lo + 1.0);
  Image image(kWidth, kHeight, Rgba8{255, 255, 255, 255});
  drawAxes(image, axes, "fitting time per stage vs vertices (log-log); " + report.cpu, "vertices", "ms");
  const Rgba8 ink{40, 40, 40, 255};
  std::int64_t legend_y = kTop;
  // Slope 1 through the first sum: where the sum stays on it, the fit scales linearly.
  const double v0 = static_cast<double>(fits.front()->vertices), t0 = stages[0].ms(*fits.front());
  if (t0 > 0.0) {
    const double v1 = std::pow(10.0, axes.x_hi);
    const double t1 = std::min(t0 * v1 / v0, std::pow(10.0, axes.y_hi));
    const double v_end = v0 * t1 / t0;
    const Rgba8 grey{150, 150, 150, 255};
    drawLine(image, axes.px(v0), axes.py(t0), axes.px(v_end), axes.py(t1), grey, 4);
    drawLine(image, kWidth - kRight + 15, static_cast<double>(legend_y + 6), kWidth - kRight + 45,
             static_cast<double>(legend_y + 6), grey, 4);
    visual::drawText(image, kWidth - kRight + 52, legend_y, "linear in vertices", ink, 1);
    legend_y += 18;
  }
  // The thesis's total for its cat (Table 6.3), the issue 6 target, as a cross.
  const double thesis_vertices = 7207.0, thesis_ms = 3.66;
  if (std::log10(thesis_ms) >= axes.y_lo) {
    const Rgba8 target{214, 39, 40, 255};
    const double x = axes.px(thesis_vertices), y = axes.py(thesis_ms);
    drawLine(image, x - 6, y - 6, x + 6, y + 6, target, 0);
    drawLine(image, x - 6, y + 6, x + 6, y - 6, target, 0);
    drawLine(image, kWidth - kRight + 24, static_cast<double>(legend_y), kWidth - kRight + 36,
             static_cast<double>(legend_y + 12), target, 0);
    drawLine(image, kWidth - kRight + 24, static_cast<double>(legend_y + 12), kWidth - kRight + 36,
             static_cast<double>(legend_y), target, 0);
    visual::drawText(image, kWidth - kRight + 52, legend_y, "thesis total, cat: 3.66 ms", ink, 1);
    legend_y += 18;
  }
  std::size_t index = 0;
  for (const StageSeries& s : stages) {
    const Rgba8 colour = index == 0 ? Rgba8{20, 20, 20, 255} : seriesColour(index - 1);
    ++index;
    std::vector<std::pair<double, double>> points;
    for (const FitStageRecord* f : fits) {
      const double ms = s.ms(*f);
      if (ms > 0.0) points.emplace_back(static_cast<double>(f->vertices), ms);
    }
    for (std::size_t i = 0; i + 1 < points.size(); ++i) {
      drawLine(image, axes.px(points[i].first), axes.py(points[i].second), axes.px(points[i + 1].first),
               axes.py(points[i + 1].second), colour, s.dash);
    }
    for (const auto& [x, y] : points) visual::fillRect(image, std::lround(axes.px(x)) - 3, std::lround(axes.py(y)) - 3, 7, 7, colour);
    drawLine(image, kWidth - kRight + 15, static_cast<double>(legend_y + 6), kWidth - kRight + 45,
             static_cast<double>(legend_y + 6), colour, s.dash);
    visual::drawText(image, kWidth - kRight + 52, legend_y, s.label, ink, 1);
    legend_y += 18;
  }
  return visual::writePng(path, image);
}

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
  LogAxes axes;
  axes.x_lo = std::floor(x_lo), axes.x_hi = std::max(std::ceil(x_hi), axes.x_lo + 1.0);
  axes.y_lo = std::floor(y_lo), axes.y_hi = std::max(std::ceil(y_hi), axes.y_lo + 1.0);
  Image image(kWidth, kHeight, Rgba8{255, 255, 255, 255});
  drawAxes(image, axes, "vertices per second vs vertices (log-log); " + report.device, "vertices", "vertices/s");
  const Rgba8 ink{40, 40, 40, 255};
  std::size_t index = 0;
  std::int64_t legend_y = kTop;
  for (const auto& [label, s] : series) {
    const Rgba8 colour = seriesColour(index++);
    for (std::size_t i = 0; i + 1 < s.points.size(); ++i) {
      drawLine(image, axes.px(s.points[i].first), axes.py(s.points[i].second), axes.px(s.points[i + 1].first),
               axes.py(s.points[i + 1].second), colour, s.dash);
    }
    for (const auto& [x, y] : s.points) visual::fillRect(image, std::lround(axes.px(x)) - 3, std::lround(axes.py(y)) - 3, 7, 7, colour);
    const double legend_line_y = static_cast<double>(legend_y + 6);
    drawLine(image, kWidth - kRight + 15, legend_line_y, kWidth - kRight + 45, legend_line_y, colour, s.dash);
    visual::drawText(image, kWidth - kRight + 52, legend_y, s.label, ink, 1);
    legend_y += 18;
  }
  return visual::writePng(path, image);
}

}  // namespace odeskin::bench
