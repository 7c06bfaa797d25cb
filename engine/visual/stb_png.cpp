// SPDX-License-Identifier: MIT
#include "stb_png.hpp"

#include <cstdlib>

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

namespace odeskin::visual {
namespace {

void appendBytes(void* context, void* data, int size) {
  static_cast<std::string*>(context)->append(static_cast<const char*>(data), static_cast<std::size_t>(size));
}

}  // namespace

bool stbEncodePng(std::string& bytes, int width, int height, int channels, const void* pixels, int stride) {
  return stbi_write_png_to_func(appendBytes, &bytes, width, height, channels, pixels, stride) != 0;
}

}  // namespace odeskin::visual
