// SPDX-License-Identifier: MIT
// Putting pictures together on the CPU: a render over its background, panels side by side, filled
// rectangles, shrinking, and contact sheets of animation frames.
#pragma once

#include <cstdint>
#include <span>
#include <string>

#include "image.hpp"

namespace odeskin::visual {

// The renderer clears to transparent black and resolves multisampling by averaging, so its pixels
// are premultiplied by coverage: out = src + (1 - src.a) background, opaque.
Image overBackground(const Image& premultiplied, Rgba8 background);

// Copies `src` with its top left corner at (x, y) of `dst`; parts outside `dst` are dropped.
void blit(Image& dst, const Image& src, std::int64_t x, std::int64_t y);

// Fills the rectangle [x, x + w) x [y, y + h), clipped to the image.
void fillRect(Image& image, std::int64_t x, std::int64_t y, std::int64_t w, std::int64_t h, Rgba8 colour);

// Area-averaging resize to width x height (both >= 1): each output pixel is the mean of the source
// pixels whose centres fall in its footprint (the nearest one when none does, as when enlarging).
Image resize(const Image& image, std::uint32_t width, std::uint32_t height);

// Frames in rows of `columns`, each shrunk to `thumb_width` wide (height in proportion, taken from
// the first frame), `gap` pixels apart and around, on `background`. Every frame should have the
// first frame's size; others are resized to it. With captions (one per frame, or empty), each is
// written in `ink` centred under its thumbnail. Empty input gives an empty image.
Image contactSheet(std::span<const Image> frames, std::uint32_t columns, std::uint32_t thumb_width, std::uint32_t gap,
                   Rgba8 background, std::span<const std::string> captions = {}, Rgba8 ink = {40, 40, 46, 255});

// Columns for a contact sheet of `count` frames with at most `max_columns` per row, balanced so the
// last row is not nearly empty (8 frames, 6 at most: 2 rows of 4).
std::uint32_t balancedColumns(std::size_t count, std::uint32_t max_columns);

}  // namespace odeskin::visual
