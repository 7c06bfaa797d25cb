// SPDX-License-Identifier: MIT
#include "png_writer.hpp"

#include <algorithm>

#include <cstdlib>
#include <vector>

#ifdef ODESKIN_HAVE_ZLIB
#include <zlib.h>

namespace {

// zlib's deflate for stb's PNG encoder: about two thirds of the size of stb's own compressor on
// rendered pictures (smooth shading), which matters for pictures kept in the repository.
unsigned char* zlibCompress(unsigned char* data, int data_len, int* out_len, int /*quality*/) {
  uLongf size = compressBound(static_cast<uLong>(data_len));
  auto* out = static_cast<unsigned char*>(std::malloc(size));  // stb frees it with free()
  if (out == nullptr) return nullptr;
  if (compress2(out, &size, data, static_cast<uLong>(data_len), Z_DEFAULT_COMPRESSION) != Z_OK) {
    std::free(out);
    return nullptr;
  }
  *out_len = static_cast<int>(size);
  return out;
}

}  // namespace
#define STBIW_ZLIB_COMPRESS zlibCompress
#endif

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
  // Opaque pictures (every composed picture) are stored as RGB: a quarter less to compress.
  const bool opaque = std::all_of(image.pixels.begin(), image.pixels.end(), [](Rgba8 p) { return p.a == 255; });
  std::vector<std::uint8_t> rgb;
  if (opaque) {
    rgb.reserve(image.pixels.size() * 3);
    for (Rgba8 p : image.pixels) rgb.insert(rgb.end(), {p.r, p.g, p.b});
  }
  const int channels = opaque ? 3 : 4;
  const void* data = opaque ? static_cast<const void*>(rgb.data()) : static_cast<const void*>(image.pixels.data());
  if (stbi_write_png_to_func(appendBytes, &bytes, w, h, channels, data, w * channels) == 0) {
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
