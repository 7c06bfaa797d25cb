// SPDX-License-Identifier: MIT
#include "png_writer.hpp"

#include <algorithm>
#include <vector>

#include "engine/io/obj_io.hpp"
#include "stb_png.hpp"

namespace odeskin::visual {

Result<std::string> encodePng(const Image& image) {
  if (image.empty() || image.width == 0 || image.height == 0) return invalidArgument("png: the image is empty");
  if (image.width > kMaxPngSide || image.height > kMaxPngSide) {
    return invalidArgument("png: " + std::to_string(image.width) + " x " + std::to_string(image.height) +
                           " is larger than 32768 pixels a side");
  }
  std::string bytes;
  const int w = static_cast<int>(image.width);
  const int h = static_cast<int>(image.height);
  // Opaque pictures (every composed picture) are stored as RGB: a quarter less to compress.
  const bool opaque = std::all_of(image.pixels.begin(), image.pixels.end(), [](Rgba8 p) { return p.a == 255; });
  std::vector<std::uint8_t> rgb;
  if (opaque) {
    rgb.reserve(image.pixels.size() * 3);
    for (Rgba8 p : image.pixels) rgb.insert(rgb.end(), {p.r, p.g, p.b});
  }
  const int channels = opaque ? 3 : 4;
  const void* data = opaque ? static_cast<const void*>(rgb.data()) : static_cast<const void*>(image.pixels.data());
  if (!stbEncodePng(bytes, w, h, channels, data, w * channels)) {
    return internalError("png: stb_image_write could not encode the image");
  }
  return bytes;
}

Status writePng(const std::filesystem::path& path, const Image& image) {
  Result<std::string> bytes = encodePng(image);
  if (!bytes.ok()) return Status(bytes.status().code(), path.string() + ": " + bytes.status().message());
  return writeFileAtomically(path, *bytes);
}

}  // namespace odeskin::visual
