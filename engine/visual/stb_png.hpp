// SPDX-License-Identifier: MIT
// stb_image_write's PNG encoder (Debian libstb-dev) behind one function, in a translation unit of
// its own: scripts/analyze.sh leaves stb's implementation (upstream code) out of clang-tidy.
#pragma once

#include <string>

namespace odeskin::visual {

// Appends the PNG of `height` rows of `stride` bytes (8-bit, `channels` 3 or 4) to `bytes`; false
// when stb cannot encode it (out of memory).
bool stbEncodePng(std::string& bytes, int width, int height, int channels, const void* pixels, int stride);

}  // namespace odeskin::visual
