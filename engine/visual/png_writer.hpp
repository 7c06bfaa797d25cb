// SPDX-License-Identifier: MIT
// PNG files through stb_image_write (Debian libstb-dev), compressed with zlib when the build found
// it (stb's own deflate otherwise): 8-bit RGB when every pixel is opaque, else RGBA; written
// atomically.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include "../core/result.hpp"
#include "image.hpp"

namespace odeskin::visual {

// Pictures up to this many pixels a side (stb's encoder works in int sizes).
inline constexpr std::uint32_t kMaxPngSide = 1u << 15;

// The PNG bytes of `image`. kInvalidArgument for an empty image or one over kMaxPngSide a side
// (far beyond what odeskin draws).
Result<std::string> encodePng(const Image& image);

// encodePng, then a temporary file beside `path` renamed into place, so a reader never sees a
// half-written picture. kIoError naming the path when it cannot be written.
Status writePng(const std::filesystem::path& path, const Image& image);

}  // namespace odeskin::visual
