// SPDX-License-Identifier: MIT
#include "compose.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "text.hpp"

namespace odeskin::visual {

Image overBackground(const Image& premultiplied, Rgba8 background) {
  Image out(premultiplied.width, premultiplied.height);
  for (std::size_t i = 0; i < premultiplied.pixels.size(); ++i) {
    const Rgba8 s = premultiplied.pixels[i];
    const int keep = 255 - s.a;
    auto mix = [keep](std::uint8_t over, std::uint8_t under) {
      return static_cast<std::uint8_t>(std::min(255, over + (keep * under + 127) / 255));
    };
    out.pixels[i] = {mix(s.r, background.r), mix(s.g, background.g), mix(s.b, background.b), 255};
  }
  return out;
}

void blit(Image& dst, const Image& src, std::int64_t x, std::int64_t y) {
  for (std::uint32_t sy = 0; sy < src.height; ++sy) {
    const std::int64_t dy = y + sy;
    if (dy < 0 || dy >= dst.height) continue;
    for (std::uint32_t sx = 0; sx < src.width; ++sx) {
      const std::int64_t dx = x + sx;
      if (dx < 0 || dx >= dst.width) continue;
      dst.at(static_cast<std::uint32_t>(dx), static_cast<std::uint32_t>(dy)) = src.at(sx, sy);
    }
  }
}

void fillRect(Image& image, std::int64_t x, std::int64_t y, std::int64_t w, std::int64_t h, Rgba8 colour) {
  const std::int64_t x0 = std::max<std::int64_t>(x, 0);
  const std::int64_t y0 = std::max<std::int64_t>(y, 0);
  const std::int64_t x1 = std::min<std::int64_t>(x + w, image.width);
  const std::int64_t y1 = std::min<std::int64_t>(y + h, image.height);
  for (std::int64_t py = y0; py < y1; ++py) {
    for (std::int64_t px = x0; px < x1; ++px) {
      image.at(static_cast<std::uint32_t>(px), static_cast<std::uint32_t>(py)) = colour;
    }
  }
}

namespace {

// Source pixels [first, last) whose centres (i + 0.5) fall in the footprint of output pixel `i`;
// the nearest one when none does (enlarging).
std::pair<std::uint32_t, std::uint32_t> footprint(std::uint32_t i, double scale, std::uint32_t size) {
  auto first_centre = [](double edge) { return std::max<std::int64_t>(0, std::llround(std::ceil(edge - 0.5))); };
  std::int64_t lo = first_centre(i * scale);
  std::int64_t hi = std::min<std::int64_t>(first_centre((i + 1) * scale), size);
  if (hi <= lo) {
    lo = std::min<std::int64_t>(static_cast<std::int64_t>((i + 0.5) * scale), std::int64_t(size) - 1);
    hi = lo + 1;
  }
  return {static_cast<std::uint32_t>(lo), static_cast<std::uint32_t>(hi)};
}

}  // namespace

Image resize(const Image& image, std::uint32_t width, std::uint32_t height) {
  Image out(width, height);
  if (image.empty() || width == 0 || height == 0) return out;
  const double sx = double(image.width) / width;
  const double sy = double(image.height) / height;
  for (std::uint32_t y = 0; y < height; ++y) {
    const auto [r0, r1] = footprint(y, sy, image.height);
    for (std::uint32_t x = 0; x < width; ++x) {
      const auto [c0, c1] = footprint(x, sx, image.width);
      std::uint32_t sum[4] = {0, 0, 0, 0};
      for (std::uint32_t r = r0; r < r1; ++r) {
        for (std::uint32_t c = c0; c < c1; ++c) {
          const Rgba8 p = image.at(c, r);
          sum[0] += p.r;
          sum[1] += p.g;
          sum[2] += p.b;
          sum[3] += p.a;
        }
      }
      const std::uint32_t count = (r1 - r0) * (c1 - c0);
      auto mean = [count](std::uint32_t s) { return static_cast<std::uint8_t>((s + count / 2) / count); };
      out.at(x, y) = {mean(sum[0]), mean(sum[1]), mean(sum[2]), mean(sum[3])};
    }
  }
  return out;
}

Image contactSheet(std::span<const Image> frames, std::uint32_t columns, std::uint32_t thumb_width, std::uint32_t gap,
                   Rgba8 background, std::span<const std::string> captions, Rgba8 ink) {
  if (frames.empty() || frames.front().empty() || columns == 0 || thumb_width == 0) return {};
  const Image& first = frames.front();
  const auto thumb_height = std::max<std::uint32_t>(
      1, static_cast<std::uint32_t>(std::lround(double(thumb_width) * first.height / first.width)));
  const int text_scale = thumb_height >= 400 ? 2 : 1;
  const std::int64_t caption_height = captions.empty() ? 0 : textSize("0", text_scale).height + std::int64_t{4} * text_scale;
  columns = std::min<std::uint32_t>(columns, static_cast<std::uint32_t>(frames.size()));
  const auto rows = static_cast<std::uint32_t>((frames.size() + columns - 1) / columns);
  const std::int64_t cell_height = thumb_height + caption_height;
  Image sheet(gap + columns * (thumb_width + gap), static_cast<std::uint32_t>(gap + rows * (cell_height + gap)),
              background);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const std::int64_t left = gap + static_cast<std::int64_t>(i % columns) * (thumb_width + gap);
    const std::int64_t top = gap + static_cast<std::int64_t>(i / columns) * (cell_height + gap);
    blit(sheet, resize(frames[i], thumb_width, thumb_height), left, top);
    if (i < captions.size()) {
      const std::int64_t width = textSize(captions[i], text_scale).width;
      drawText(sheet, left + (std::int64_t(thumb_width) - width) / 2, top + thumb_height + text_scale, captions[i], ink,
               text_scale);
    }
  }
  return sheet;
}

std::uint32_t balancedColumns(std::size_t count, std::uint32_t max_columns) {
  if (count == 0 || max_columns == 0) return 1;
  const std::size_t rows = (count + max_columns - 1) / max_columns;
  return static_cast<std::uint32_t>((count + rows - 1) / rows);
}

}  // namespace odeskin::visual
