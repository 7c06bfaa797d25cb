// SPDX-License-Identifier: MIT
#include "png_writer.hpp"

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC  // private to this file: no clash with another copy of stb
#define STBI_WRITE_NO_STDIO     // bytes only; files go through writeFileAtomically
#include <stb_image_write.h>

#include "engine/io/obj_io.hpp"

namespace odeskin::visual {
namespace {

constexpr std::uint32_t kMaxSide = 1u << 15;

void appendBytes(void* context, void* data, int size) {
  static_cast<std::string*>(context)->append(static_cast<const char*>(data), static_cast<std::size_t>(size));
}

}  // namespace

Result<std::string> encodePng(const Image& image) {
  if (image.empty() || image.width == 0 || image.height == 0) return invalidArgument("png: the image is empty");
  if (image.width > kMaxSide || image.height > kMaxSide) {
    return invalidArgument("png: " + std::to_string(image.width) + " x " + std::to_string(image.height) +
                           " is larger than 32768 pixels a side");
  }
  std::string bytes;
  const int w = static_cast<int>(image.width);
  const int h = static_cast<int>(image.height);
  if (stbi_write_png_to_func(appendBytes, &bytes, w, h, 4, image.pixels.data(), w * 4) == 0) {
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
