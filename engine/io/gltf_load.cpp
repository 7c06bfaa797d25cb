// SPDX-License-Identifier: MIT
#include "gltf_load.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <exception>
#include <functional>
#include <fstream>
#include <limits>
#include <optional>
#include <string_view>
#include <system_error>
#include <vector>

#include <nlohmann/json.hpp>

#include "gltf_meshopt.hpp"

namespace odeskin::gltf {
namespace {

constexpr std::array<std::string_view, 6> kGeometryNeutralExtensions{
    "KHR_texture_transform", "KHR_texture_basisu", "EXT_texture_webp",
    "EXT_texture_avif",      "KHR_lights_punctual", "KHR_materials_"};

bool handled(std::string_view name) {
  if (name == "KHR_mesh_quantization" || name == kMeshoptExtension) return true;
  return std::any_of(kGeometryNeutralExtensions.begin(), kGeometryNeutralExtensions.end(), [&](std::string_view e) {
    return e.back() == '_' ? name.starts_with(e) : name == e;
  });
}

bool skipImage(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
  return true;
}

bool keepEncodedImage(tinygltf::Image* image, const int, std::string*, std::string*, int, int, const unsigned char* bytes,
                      int size, void*) {
  image->image.assign(bytes, bytes + size);
  image->as_is = true;
  return true;
}

std::string trimmed(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == '\r' || s.back() == ' ')) s.pop_back();
  return s;
}

// tinygltf quotes a buffer's whole URI in its errors: a data: URI is the buffer itself, megabytes of
// base64 in one message line. Each is cut to its head and its length.
std::string withShortDataUris(std::string s) {
  constexpr std::size_t kKept = 48;
  for (std::size_t at = s.find("data:"); at != std::string::npos; at = s.find("data:", at + 1)) {
    std::size_t end = at;
    while (end < s.size() && s[end] != '\'' && s[end] != '"' && s[end] != ' ' && s[end] != '\n') ++end;
    if (end - at > kKept) s.replace(at + kKept, end - at - kKept, "... (" + std::to_string(end - at) + " characters)");
  }
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

// The whole of `path` into `out`, or why not (the message leaves the path out): the glTF file
// itself and every external file it names are read by this one rule.
template <typename Bytes>
Status readWholeRegularFile(const std::filesystem::path& path, Bytes& out) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return ioError("no such file");
  if (!std::filesystem::is_regular_file(path, ec)) return ioError("not a regular file");
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) return ioError("cannot read its size: " + ec.message());
  if (size > static_cast<std::uintmax_t>(std::numeric_limits<std::int32_t>::max())) {
    return ioError(std::to_string(size) + " bytes, over the 2 GiB tinygltf 2.7 can read");
  }
  std::ifstream file(path, std::ios::binary);
  if (!file) return ioError("cannot open for reading");
  out.resize(static_cast<std::size_t>(size));
  file.read(reinterpret_cast<char*>(out.data()), static_cast<std::streamsize>(size));
  if (file.gcount() != static_cast<std::streamsize>(size)) return ioError("read failed");
  return okStatus();
}

// File callbacks for a glTF read from disk. tinygltf 2.7's own open any path it is given and read
// it whole before comparing its size with the buffer's byteLength: a URI naming a FIFO blocked the
// read forever, and one naming a file of many gigabytes read all of it. Only regular files up to
// 2 GiB (what tinygltf 2.7 can index) are read here.
bool existingFile(const std::string& path, void*) {  // of any kind: readRegularFile says why not
  std::error_code ec;
  return std::filesystem::exists(path, ec);
}
bool readRegularFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void*) {
  const Status read = readWholeRegularFile(path, *out);
  if (!read.ok() && err) *err += read.message();
  return read.ok();
}

bool isGlb(std::string_view first_bytes) { return first_bytes.substr(0, 4) == "glTF"; }

std::uint32_t littleEndian32(std::string_view bytes, std::size_t at) {
  std::uint32_t v = 0;
  for (std::size_t k = 0; k < 4; ++k) v |= std::uint32_t{static_cast<unsigned char>(bytes[at + k])} << (8 * k);
  return v;
}

// An unsigned integer member of a JSON object, or nothing (tinygltf reports what is malformed).
std::optional<std::uint64_t> unsignedMember(const nlohmann::json& object, const char* name) {
  const auto it = object.find(name);
  if (it == object.end() || !it->is_number_unsigned()) return std::nullopt;
  return it->get<std::uint64_t>();
}

// Whether the quote at `at` is escaped: an odd run of backslashes before it. The run stops at the
// string's opening quote at the latest.
bool escaped(std::string_view json, std::size_t at) {
  std::size_t slashes = 0;
  while (json[at - 1 - slashes] == '\\') ++slashes;
  return slashes % 2 == 1;
}

// How deep the JSON text's arrays and objects nest, counted without parsing it: strings are
// skipped whole with memchr, so a .gltf whose buffers are megabytes of base64 costs little.
int jsonNesting(std::string_view json) {
  int depth = 0;
  int deepest = 0;
  for (std::size_t i = 0; i < json.size(); ++i) {
    const char c = json[i];
    if (c == '"') {
      do {  // to the next quote that an even run of backslashes (or none) precedes
        const void* quote = std::memchr(json.data() + i + 1, '"', json.size() - i - 1);
        if (!quote) return deepest;
        i = static_cast<std::size_t>(static_cast<const char*>(quote) - json.data());
      } while (escaped(json, i));
    } else if (c == '[' || c == '{') {
      deepest = std::max(deepest, ++depth);
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return deepest;
}

// glTF's own structure nests about ten deep; "extras" and "extensions" hold anything, and
// tinygltf 2.7 copies them into its Value type recursively, one stack frame per level.
constexpr int kMaxJsonDepth = 256;

// What tinygltf 2.7 does not check in the glTF JSON (a .gltf file, or a GLB's JSON chunk), where it
// crashes, costs memory or reaches outside the input. JSON nested too deep overflows its stack (a
// 400 KB .gltf of nested arrays in "extras" crashed odeskin). It copies a GLB's BIN chunk into
// every buffer without a uri, so a few bytes of JSON naming many such buffers multiply the file in
// memory (the spec lets only one buffer stand for the chunk). And it takes the address of an
// image's first byte in its buffer without checking that the bufferView lies inside it. Anything
// malformed is left for tinygltf to report in its own words.
Status checkJson(std::string_view json, bool glb, const std::string& source) {
  const int deepest = jsonNesting(json);
  if (deepest > kMaxJsonDepth) {
    return parseError(source + ": its JSON nests " + std::to_string(deepest) + " levels deep, beyond the " +
                      std::to_string(kMaxJsonDepth) + " odeskin reads");
  }
  // The rest needs the document; a .gltf without images has nothing left to check, and parsing
  // megabytes of base64 twice would cost a fifth of the whole read. (A key may be spelt with
  // \u escapes, so text with any is parsed. The search starts at a quote, which base64 lacks:
  // searching for a letter would stop at every sixty-fourth character.)
  if (!glb && json.find("\"images\"") == std::string_view::npos && json.find("\\u") == std::string_view::npos) {
    return okStatus();
  }
  const nlohmann::json doc = nlohmann::json::parse(json, nullptr, /*allow_exceptions=*/false);
  if (!doc.is_object()) return okStatus();
  const auto array = [&](const char* name) {
    const auto it = doc.find(name);
    return it != doc.end() && it->is_array() ? &*it : nullptr;
  };
  const nlohmann::json* buffers = array("buffers");
  if (glb && buffers) {
    std::optional<std::size_t> first;
    for (std::size_t b = 0; b < buffers->size(); ++b) {
      if (!(*buffers)[b].is_object() || (*buffers)[b].contains("uri")) continue;
      if (first) {
        return parseError(source + ": buffers " + std::to_string(*first) + " and " + std::to_string(b) +
                          " both have no uri; in a GLB only the first buffer may stand for the BIN chunk");
      }
      first = b;
    }
  }
  const nlohmann::json* views = array("bufferViews");
  const nlohmann::json* images = array("images");
  if (!buffers || !views || !images) return okStatus();
  for (std::size_t i = 0; i < images->size(); ++i) {
    if (!(*images)[i].is_object()) continue;
    const std::optional<std::uint64_t> v = unsignedMember((*images)[i], "bufferView");
    if (!v || *v >= views->size() || !(*views)[*v].is_object()) continue;
    const nlohmann::json& view = (*views)[*v];
    const std::optional<std::uint64_t> b = unsignedMember(view, "buffer");
    if (!b || *b >= buffers->size() || !(*buffers)[*b].is_object()) continue;
    const std::optional<std::uint64_t> size = unsignedMember((*buffers)[*b], "byteLength");
    const std::uint64_t offset = unsignedMember(view, "byteOffset").value_or(0);
    const std::uint64_t length = unsignedMember(view, "byteLength").value_or(0);
    if (size && (offset >= *size || length > *size - offset)) {
      return parseError(source + ": image " + std::to_string(i) + "'s bufferView " + std::to_string(*v) +
                        " (byteOffset " + std::to_string(offset) + ", byteLength " + std::to_string(length) +
                        ") lies outside buffer " + std::to_string(*b) + " (" + std::to_string(*size) + " bytes)");
    }
  }
  return okStatus();
}

// A GLB's JSON chunk, or nothing when the file is too short for the header or the chunk runs past
// the file or its declared length (tinygltf reports those).
std::optional<std::string_view> glbJsonChunk(std::string_view bytes) {
  if (bytes.size() < 20) return std::nullopt;
  const std::uint64_t length = std::min<std::uint64_t>(littleEndian32(bytes, 8), bytes.size());
  const std::uint64_t json_length = littleEndian32(bytes, 12);
  if (20 + json_length > length) return std::nullopt;
  return bytes.substr(20, static_cast<std::size_t>(json_length));
}

// The GLB container (glTF 2.0, "Binary glTF Layout"). tinygltf 2.7 checks a BIN chunk's length
// against the file's total length without the chunk's own 8-byte header, so a chunk declared up to
// 8 bytes longer than what follows it passes, and tinygltf then copies those bytes from past the
// end of its input into the buffer: a heap over-read, and bytes from outside the file in the
// geometry. Then the JSON chunk (checkJson). Everything else about the layout tinygltf checks and
// reports itself.
Status checkGlb(std::string_view bytes, const std::string& source) {
  const std::optional<std::string_view> json = glbJsonChunk(bytes);
  if (!json) return okStatus();
  ODESKIN_TRY(checkJson(*json, true, source));
  const std::uint64_t length = std::min<std::uint64_t>(littleEndian32(bytes, 8), bytes.size());
  const std::uint64_t bin_header = 20 + json->size();  // past the JSON chunk
  if (bin_header + 8 > length) return okStatus();
  const std::uint64_t bin_length = littleEndian32(bytes, static_cast<std::size_t>(bin_header));
  if (bin_header + 8 + bin_length > length) {
    return parseError(source + ": the GLB's second chunk declares " + std::to_string(bin_length) +
                      " bytes from byte " + std::to_string(bin_header + 8) + ", past the end of its " +
                      std::to_string(length) + " bytes (truncated or corrupted)");
  }
  return okStatus();
}

// The file with its EXT_meshopt_compression placeholder buffers replaced (gltf_meshopt.hpp), or
// nullopt when it has none, or when its JSON is too deep or its GLB framing too broken to look at
// (the checks that follow report those).
std::optional<std::string> withMeshoptPlaceholdersReplaced(const std::string& bytes, bool glb) {
  const std::optional<std::string_view> json = glb ? glbJsonChunk(bytes) : std::optional<std::string_view>(bytes);
  // Most files do not use the extension: a search for its name spares them the nesting scan and the parse.
  if (!json || json->find(kMeshoptExtension) == std::string_view::npos || jsonNesting(*json) > kMaxJsonDepth) {
    return std::nullopt;
  }
  std::optional<std::string> replaced = withoutMeshoptPlaceholders(*json, glb);
  if (!replaced || !glb) return replaced;
  const std::uint64_t declared = littleEndian32(bytes, 8);
  const std::uint64_t json_length = json->size();
  replaced->append((4 - replaced->size() % 4) % 4, ' ');  // chunks are 4-byte aligned
  auto put32 = [](std::string& out, std::size_t at, std::uint64_t value) {
    for (std::size_t k = 0; k < 4; ++k) out[at + k] = static_cast<char>((value >> (8 * k)) & 0xff);
  };
  std::string out = bytes.substr(0, 20);  // header and JSON chunk header, lengths rewritten below
  put32(out, 8, declared - json_length + replaced->size());
  put32(out, 12, replaced->size());
  out += *replaced;
  out.append(bytes, static_cast<std::size_t>(20 + json_length));  // the BIN chunk, as it was
  return out;
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
    err = withShortDataUris(trimmed(err));
    return parseError(source + ": tinygltf cannot read it: " + (err.empty() ? "no reason given" : err));
  }
  return model;
}

// A .gltf or .glb held in memory. `base_dir`: the folder external files are found in, or null for
// bytes with no folder (every external URI refused, nothing written). `keep_images`: each image's
// encoded bytes are kept (keepEncodedImage) instead of dropped.
Result<tinygltf::Model> loadBytes(const std::string& bytes, const std::string& source, const std::string* base_dir,
                                  bool keep_images = false) {
  if (bytes.size() > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max())) {
    return ioError(source + ": " + std::to_string(bytes.size()) + " bytes, over the 2 GiB tinygltf 2.7 can read");
  }
  const bool glb = isGlb(bytes);
  // tinygltf's own words for these are "JSON string too short".
  if (bytes.empty()) return parseError(source + ": the file is empty");
  if (!glb && bytes.size() < 4) return parseError(source + ": " + std::to_string(bytes.size()) + " bytes, too short to be glTF");
  const std::optional<std::string> replaced = withMeshoptPlaceholdersReplaced(bytes, glb);
  const std::string& input = replaced ? *replaced : bytes;
  ODESKIN_TRY(glb ? checkGlb(input, source) : checkJson(input, false, source));
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(keep_images ? keepEncodedImage : skipImage, nullptr);
  loader.SetFsCallbacks(base_dir ? tinygltf::FsCallbacks{existingFile, samePath, readRegularFile, noWrite, nullptr}
                                 : tinygltf::FsCallbacks{noFile, samePath, noRead, noWrite, nullptr});
  const std::string folder = base_dir ? *base_dir : std::string();
  if (input.size() > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max())) {
    return ioError(source + ": " + std::to_string(input.size()) + " bytes, over the 2 GiB tinygltf 2.7 can read");
  }
  const auto length = static_cast<unsigned int>(input.size());
  ODESKIN_ASSIGN_OR_RETURN(tinygltf::Model model,
                           runLoader(source, [&](tinygltf::Model& m, std::string& err, std::string& warn) {
                             return glb ? loader.LoadBinaryFromMemory(&m, &err, &warn,
                                                                      reinterpret_cast<const unsigned char*>(input.data()),
                                                                      length, folder)
                                        : loader.LoadASCIIFromString(&m, &err, &warn, input.data(), length, folder);
                           }));
  ODESKIN_TRY(decodeMeshoptViews(model, source));
  return model;
}

}  // namespace

Result<tinygltf::Model> loadModel(const std::filesystem::path& path) {
  std::string bytes;
  if (Status read = readWholeRegularFile(path, bytes); !read.ok()) return ioError(path.string() + ": " + read.message());
  const std::string folder = path.parent_path().string();  // where tinygltf finds external buffers
  return loadBytes(bytes, path.string(), &folder);
}

Result<tinygltf::Model> loadModelWithImages(const std::filesystem::path& path) {
  std::string bytes;
  if (Status read = readWholeRegularFile(path, bytes); !read.ok()) return ioError(path.string() + ": " + read.message());
  const std::string folder = path.parent_path().string();
  return loadBytes(bytes, path.string(), &folder, true);
}

Result<tinygltf::Model> loadModelFromMemory(const std::string& bytes, const std::string& source) {
  return loadBytes(bytes, source, nullptr);
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
