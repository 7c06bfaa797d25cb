// SPDX-License-Identifier: MIT
#include "gltf_load.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <exception>
#include <functional>
#include <fstream>
#include <limits>
#include <string_view>
#include <system_error>
#include <vector>

#include <nlohmann/json.hpp>

namespace odeskin::gltf {
namespace {

constexpr std::array<std::string_view, 6> kGeometryNeutralExtensions{
    "KHR_texture_transform", "KHR_texture_basisu", "EXT_texture_webp",
    "EXT_texture_avif",      "KHR_lights_punctual", "KHR_materials_"};

bool handled(std::string_view name) {
  if (name == "KHR_mesh_quantization") return true;
  return std::any_of(kGeometryNeutralExtensions.begin(), kGeometryNeutralExtensions.end(), [&](std::string_view e) {
    return e.back() == '_' ? name.starts_with(e) : name == e;
  });
}

bool skipImage(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
  return true;
}

std::string trimmed(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == '\r' || s.back() == ' ')) s.pop_back();
  return s;
}

// File callbacks for glTF held in memory: it has no folder, so a buffer URI that is not a data: URI
// names nothing, and nothing is ever written.
bool noFile(const std::string&, void*) { return false; }
std::string samePath(const std::string& path, void*) { return path; }
bool noRead(std::vector<unsigned char>*, std::string* err, const std::string& path, void*) {
  if (err) *err += "external file '" + path + "' cannot be read: the glTF is held in memory\n";
  return false;
}
bool noWrite(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "odeskin never writes while reading glTF\n";
  return false;
}

bool isGlb(std::string_view first_bytes) { return first_bytes.substr(0, 4) == "glTF"; }

std::uint32_t littleEndian32(std::string_view bytes, std::size_t at) {
  std::uint32_t v = 0;
  for (std::size_t k = 0; k < 4; ++k) v |= std::uint32_t{static_cast<unsigned char>(bytes[at + k])} << (8 * k);
  return v;
}

// tinygltf 2.7 copies a GLB's BIN chunk into every buffer without a uri, so a few bytes of JSON
// naming many such buffers multiply the file in memory. The spec lets only the first buffer be the
// BIN chunk; two without a uri are refused before tinygltf sees them.
Status checkGlbBuffers(const std::string& json_chunk, const std::string& source) {
  const nlohmann::json doc = nlohmann::json::parse(json_chunk, nullptr, /*allow_exceptions=*/false);
  const auto buffers = doc.is_object() ? doc.find("buffers") : doc.end();
  if (!doc.is_object() || buffers == doc.end() || !buffers->is_array()) return okStatus();  // tinygltf's to report
  std::size_t first = buffers->size();
  for (std::size_t b = 0; b < buffers->size(); ++b) {
    const nlohmann::json& buffer = (*buffers)[b];
    if (!buffer.is_object() || buffer.contains("uri")) continue;
    if (first < b) {
      return parseError(source + ": buffers " + std::to_string(first) + " and " + std::to_string(b) +
                        " both have no uri; in a GLB only the first buffer may stand for the BIN chunk");
    }
    first = b;
  }
  return okStatus();
}

// The GLB container (glTF 2.0, "Binary glTF Layout"). tinygltf 2.7 checks a BIN chunk's length
// against the file's total length without the chunk's own 8-byte header, so a chunk declared up to
// 8 bytes longer than what follows it passes, and tinygltf then copies those bytes from past the
// end of its input into the buffer: a heap over-read, and bytes from outside the file in the
// geometry. Then the buffers (checkGlbBuffers). Everything else about the layout tinygltf checks
// and reports itself. `read(offset, n)` returns the file's n bytes from offset (fewer at its end).
Status checkGlbChunks(const std::function<std::string(std::uint64_t, std::size_t)>& read, std::uint64_t size,
                      const std::string& source) {
  const std::string header = read(0, 20);
  if (header.size() < 20) return okStatus();
  const std::uint64_t length = std::min<std::uint64_t>(littleEndian32(header, 8), size);
  const std::uint64_t json_length = littleEndian32(header, 12);
  const std::uint64_t bin_header = 20 + json_length;  // past the JSON chunk
  if (bin_header <= length) ODESKIN_TRY(checkGlbBuffers(read(20, static_cast<std::size_t>(json_length)), source));
  if (bin_header + 8 > length) return okStatus();
  const std::string chunk = read(bin_header, 8);
  if (chunk.size() < 8) return okStatus();
  const std::uint64_t bin_length = littleEndian32(chunk, 0);
  if (bin_header + 8 + bin_length > length) {
    return parseError(source + ": the GLB's second chunk declares " + std::to_string(bin_length) +
                      " bytes from byte " + std::to_string(bin_header + 8) + ", past the end of its " +
                      std::to_string(length) + " bytes (truncated or corrupted)");
  }
  return okStatus();
}

// tinygltf's load (it reports a bad file by returning false, but a few paths throw).
Result<tinygltf::Model> runLoader(const std::string& source,
                                  const std::function<bool(tinygltf::Model&, std::string&, std::string&)>& load) {
  tinygltf::Model model;
  std::string err;
  bool ok = false;
  try {
    std::string warn;  // tinygltf's warnings: nothing odeskin reports
    ok = load(model, err, warn);
  } catch (const std::exception& e) {
    err = e.what();
    ok = false;
  }
  if (!ok) {
    err = trimmed(err);
    return parseError(source + ": tinygltf cannot read it: " + (err.empty() ? "no reason given" : err));
  }
  return model;
}

}  // namespace

Result<tinygltf::Model> loadModel(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return ioError(path.string() + ": no such file");
  if (!std::filesystem::is_regular_file(path, ec)) return ioError(path.string() + ": not a regular file");
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) return ioError(path.string() + ": cannot read its size: " + ec.message());
  if (size > static_cast<std::uintmax_t>(std::numeric_limits<std::int32_t>::max())) {
    return ioError(path.string() + ": " + std::to_string(size) + " bytes, over the 2 GiB tinygltf 2.7 can read");
  }
  std::ifstream file(path, std::ios::binary);
  if (!file) return ioError(path.string() + ": cannot open for reading");
  const auto read = [&](std::uint64_t offset, std::size_t n) {
    std::string bytes(n, '\0');
    file.clear();
    file.seekg(static_cast<std::streamoff>(offset));
    file.read(bytes.data(), static_cast<std::streamsize>(n));
    bytes.resize(static_cast<std::size_t>(std::max<std::streamsize>(file.gcount(), 0)));
    return bytes;
  };
  const bool binary = isGlb(read(0, 4));
  if (binary) ODESKIN_TRY(checkGlbChunks(read, size, path.string()));
  file.close();

  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(skipImage, nullptr);
  return runLoader(path.string(), [&](tinygltf::Model& model, std::string& err, std::string& warn) {
    return binary ? loader.LoadBinaryFromFile(&model, &err, &warn, path.string())
                  : loader.LoadASCIIFromFile(&model, &err, &warn, path.string());
  });
}

Result<tinygltf::Model> loadModelFromMemory(const std::string& bytes, const std::string& source) {
  if (bytes.size() > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max())) {
    return ioError(source + ": " + std::to_string(bytes.size()) + " bytes, over the 2 GiB tinygltf 2.7 can read");
  }
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(skipImage, nullptr);
  loader.SetFsCallbacks(tinygltf::FsCallbacks{noFile, samePath, noRead, noWrite, nullptr});
  if (isGlb(bytes)) {
    const auto read = [&](std::uint64_t offset, std::size_t n) {
      return offset >= bytes.size() ? std::string() : bytes.substr(static_cast<std::size_t>(offset), n);
    };
    ODESKIN_TRY(checkGlbChunks(read, bytes.size(), source));
  }
  const auto length = static_cast<unsigned int>(bytes.size());
  return runLoader(source, [&](tinygltf::Model& model, std::string& err, std::string& warn) {
    return isGlb(bytes) ? loader.LoadBinaryFromMemory(&model, &err, &warn,
                                                      reinterpret_cast<const unsigned char*>(bytes.data()), length, "")
                        : loader.LoadASCIIFromString(&model, &err, &warn, bytes.data(), length, "");
  });
}

Status checkRequiredExtensions(const tinygltf::Model& model) {
  for (const std::string& name : model.extensionsRequired) {
    if (!handled(name)) {
      return invalidArgument("requires extension " + name + ", which odeskin does not implement");
    }
  }
  return okStatus();
}

bool usesMeshQuantization(const tinygltf::Model& model) {
  auto has = [](const std::vector<std::string>& list) {
    return std::find(list.begin(), list.end(), "KHR_mesh_quantization") != list.end();
  };
  return has(model.extensionsUsed) || has(model.extensionsRequired);
}

}  // namespace odeskin::gltf
