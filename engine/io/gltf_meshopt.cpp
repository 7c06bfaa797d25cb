// SPDX-License-Identifier: MIT
#include "gltf_meshopt.hpp"

#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <meshoptimizer.h>
#include <nlohmann/json.hpp>

#include "../core/result.hpp"

namespace odeskin::gltf {
namespace {

// A one-byte data: URI: tinygltf 2.7 refuses an empty one.
constexpr const char* kOneByteUri = "data:application/octet-stream;base64,AA==";

// Decoded bytes a file may ask for: a floor for small files, then in proportion to what it holds.
// gltfpack's outputs expand about 4x (the horse: 0.68 MB to 2.5 MB); constant data compresses far
// more, but a few kilobytes must not claim gigabytes.
constexpr std::uint64_t kDecodedFloor = std::uint64_t{16} << 20;
constexpr std::uint64_t kDecodedPerByte = 32;

bool usesExtension(const nlohmann::json& doc) {
  const auto used = doc.find("extensionsUsed");
  if (used == doc.end() || !used->is_array()) return false;
  for (const nlohmann::json& name : *used) {
    if (name.is_string() && name.get<std::string>() == kMeshoptExtension) return true;
  }
  return false;
}

bool taggedFallback(const nlohmann::json& buffer) {
  const auto ext = buffer.find("extensions");
  if (ext == buffer.end() || !ext->is_object()) return false;
  const auto meshopt = ext->find(kMeshoptExtension);
  if (meshopt == ext->end() || !meshopt->is_object()) return false;
  const auto fallback = meshopt->find("fallback");
  return fallback != meshopt->end() && fallback->is_boolean() && fallback->get<bool>();
}

// The extension object's fields, read from tinygltf's Value.
struct Compressed {
  std::uint64_t buffer = 0, byte_offset = 0, byte_length = 0, byte_stride = 0, count = 0;
  std::string mode, filter = "NONE";
};

Status viewError(const std::string& source, std::size_t view, const std::string& what) {
  return parseError(source + ": bufferView " + std::to_string(view) + "'s " + kMeshoptExtension + " " + what);
}

// A whole number in [0, 2^53], or nothing.
std::optional<std::uint64_t> wholeNumber(const tinygltf::Value& object, const char* key) {
  if (!object.Has(key)) return std::nullopt;
  const tinygltf::Value& v = object.Get(key);
  if (!v.IsNumber()) return std::nullopt;
  const double d = v.GetNumberAsDouble();
  if (!(d >= 0.0 && d <= 9007199254740992.0) || std::floor(d) != d) return std::nullopt;
  return static_cast<std::uint64_t>(d);
}

Result<Compressed> readCompressed(const tinygltf::Value& ext, const std::string& source, std::size_t view) {
  if (!ext.IsObject()) return viewError(source, view, "is not an object");
  Compressed c;
  const std::pair<const char*, std::uint64_t*> required[] = {
      {"buffer", &c.buffer}, {"byteLength", &c.byte_length}, {"byteStride", &c.byte_stride}, {"count", &c.count}};
  for (const auto& [key, field] : required) {
    const std::optional<std::uint64_t> v = wholeNumber(ext, key);
    if (!v) return viewError(source, view, std::string("has no whole, non-negative \"") + key + "\"");
    *field = *v;
  }
  if (ext.Has("byteOffset")) {
    const std::optional<std::uint64_t> v = wholeNumber(ext, "byteOffset");
    if (!v) return viewError(source, view, "has a byteOffset that is not a whole, non-negative number");
    c.byte_offset = *v;
  }
  if (!ext.Has("mode") || !ext.Get("mode").IsString()) return viewError(source, view, "has no \"mode\"");
  c.mode = ext.Get("mode").Get<std::string>();
  if (ext.Has("filter")) {
    if (!ext.Get("filter").IsString()) return viewError(source, view, "has a \"filter\" that is not a string");
    c.filter = ext.Get("filter").Get<std::string>();
  }
  return c;
}

// The rules of the extension's "JSON schema updates" section.
Status checkRules(const Compressed& c, const tinygltf::BufferView& parent, const std::string& source, std::size_t view) {
  const std::string stride = "byteStride " + std::to_string(c.byte_stride);
  if (parent.byteStride != 0 && parent.byteStride != c.byte_stride) {
    return viewError(source, view, "has " + stride + " but the bufferView " + std::to_string(parent.byteStride));
  }
  if (c.byte_stride == 0 || c.count > std::numeric_limits<std::uint64_t>::max() / c.byte_stride ||
      c.byte_stride * c.count != parent.byteLength) {
    return viewError(source, view, "holds " + std::to_string(c.count) + " elements of " + std::to_string(c.byte_stride) +
                                       " bytes, not the bufferView's byteLength " + std::to_string(parent.byteLength));
  }
  if (c.mode == "ATTRIBUTES") {
    if (c.byte_stride % 4 != 0 || c.byte_stride > 256) {
      return viewError(source, view, "mode ATTRIBUTES needs a byteStride divisible by 4 and at most 256, not " +
                                         std::to_string(c.byte_stride));
    }
    if (c.filter == "NONE") return okStatus();
    if (c.filter == "OCTAHEDRAL" && (c.byte_stride == 4 || c.byte_stride == 8)) return okStatus();
    if (c.filter == "QUATERNION" && c.byte_stride == 8) return okStatus();
    if (c.filter == "EXPONENTIAL") return okStatus();
    if (c.filter == "OCTAHEDRAL" || c.filter == "QUATERNION") {
      return viewError(source, view, "filter " + c.filter + " does not allow " + stride);
    }
    return viewError(source, view, "has the unknown filter \"" + c.filter + "\"");
  }
  if (c.mode == "TRIANGLES" || c.mode == "INDICES") {
    if (c.byte_stride != 2 && c.byte_stride != 4) {
      return viewError(source, view, "mode " + c.mode + " needs a byteStride of 2 or 4, not " + std::to_string(c.byte_stride));
    }
    if (c.mode == "TRIANGLES" && c.count % 3 != 0) {
      return viewError(source, view, "mode TRIANGLES needs a count divisible by 3, not " + std::to_string(c.count));
    }
    if (c.filter != "NONE") return viewError(source, view, "mode " + c.mode + " takes no filter, not " + c.filter);
    return okStatus();
  }
  return viewError(source, view, "has the unknown mode \"" + c.mode + "\"");
}

Status decodeInto(const Compressed& c, const unsigned char* bytes, std::vector<unsigned char>& out,
                  const std::string& source, std::size_t view) {
  const auto n = static_cast<std::size_t>(c.count);
  const auto stride = static_cast<std::size_t>(c.byte_stride);
  const auto length = static_cast<std::size_t>(c.byte_length);
  int result = 0;
  if (c.mode == "ATTRIBUTES") {
    result = meshopt_decodeVertexBuffer(out.data(), n, stride, bytes, length);
  } else if (c.mode == "TRIANGLES") {
    result = meshopt_decodeIndexBuffer(out.data(), n, stride, bytes, length);
  } else {
    result = meshopt_decodeIndexSequence(out.data(), n, stride, bytes, length);
  }
  if (result != 0) {
    return viewError(source, view, "data (mode " + c.mode + ", " + std::to_string(length) +
                                       " bytes) does not decode: meshoptimizer 0.18 returned " + std::to_string(result) +
                                       " (a truncated stream, another mode's data, or a later bitstream version)");
  }
  if (c.filter == "OCTAHEDRAL") meshopt_decodeFilterOct(out.data(), n, stride);
  if (c.filter == "QUATERNION") meshopt_decodeFilterQuat(out.data(), n, stride);
  if (c.filter == "EXPONENTIAL") meshopt_decodeFilterExp(out.data(), n, stride);
  return okStatus();
}

}  // namespace

std::optional<std::string> withoutMeshoptPlaceholders(std::string_view json, bool glb) {
  nlohmann::json doc = nlohmann::json::parse(json, nullptr, /*allow_exceptions=*/false);
  if (!doc.is_object() || !usesExtension(doc)) return std::nullopt;
  const auto buffers = doc.find("buffers");
  if (buffers == doc.end() || !buffers->is_array()) return std::nullopt;
  bool changed = false;
  for (std::size_t b = 0; b < buffers->size(); ++b) {
    nlohmann::json& buffer = (*buffers)[b];
    if (!buffer.is_object()) continue;
    const bool placeholder = !buffer.contains("uri") && !(glb && b == 0);
    if (!placeholder && !taggedFallback(buffer)) continue;
    buffer["uri"] = kOneByteUri;
    buffer["byteLength"] = 1;
    changed = true;
  }
  if (!changed) return std::nullopt;
  // Invalid UTF-8 in names would make dump() throw; tinygltf would keep those bytes, and odeskin
  // reads no text from them that a replacement character could change.
  return doc.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

Status decodeMeshoptViews(tinygltf::Model& model, const std::string& source) {
  std::uint64_t file_bytes = 0;
  for (const tinygltf::Buffer& b : model.buffers) file_bytes += b.data.size();
  const std::uint64_t limit = kDecodedFloor + kDecodedPerByte * file_bytes;
  std::uint64_t decoded = 0;
  // The loop appends a buffer per decoded view; compressed data comes from the file's own buffers.
  const std::size_t file_buffers = model.buffers.size();
  const std::size_t views = model.bufferViews.size();
  for (std::size_t v = 0; v < views; ++v) {
    const auto& extensions = model.bufferViews[v].extensions;
    if (extensions.count("KHR_meshopt_compression") != 0) {
      return invalidArgument(source + ": bufferView " + std::to_string(v) +
                             " is compressed with KHR_meshopt_compression, whose later bitstreams the meshoptimizer "
                             "0.18 odeskin builds with cannot read; re-export with EXT_meshopt_compression (gltfpack "
                             "-c) or uncompressed");
    }
    const auto ext = extensions.find(kMeshoptExtension);
    if (ext == extensions.end()) continue;
    ODESKIN_ASSIGN_OR_RETURN(const Compressed c, readCompressed(ext->second, source, v));
    ODESKIN_TRY(checkRules(c, model.bufferViews[v], source, v));
    if (c.buffer >= file_buffers) {
      return viewError(source, v, "names buffer " + std::to_string(c.buffer) + " of " + std::to_string(file_buffers));
    }
    const std::vector<unsigned char>& from = model.buffers[c.buffer].data;
    if (c.byte_offset > from.size() || c.byte_length > from.size() - c.byte_offset) {
      return viewError(source, v, "bytes " + std::to_string(c.byte_offset) + " + " + std::to_string(c.byte_length) +
                                      " lie outside buffer " + std::to_string(c.buffer) + " (" +
                                      std::to_string(from.size()) + " bytes)");
    }
    const std::uint64_t size = model.bufferViews[v].byteLength;
    if (size > limit - decoded) {
      return viewError(source, v, "would decode " + std::to_string(size) + " bytes, past the " + std::to_string(limit) +
                                      " this file may decode (16 MiB and 32 per byte of its buffers)");
    }
    decoded += size;
    tinygltf::Buffer out;
    out.name = kDecodedBufferName;
    out.data.resize(static_cast<std::size_t>(size));
    ODESKIN_TRY(decodeInto(c, from.data() + c.byte_offset, out.data, source, v));
    model.buffers.push_back(std::move(out));
    model.bufferViews[v].buffer = static_cast<int>(model.buffers.size() - 1);
    model.bufferViews[v].byteOffset = 0;
  }
  return okStatus();
}

}  // namespace odeskin::gltf
