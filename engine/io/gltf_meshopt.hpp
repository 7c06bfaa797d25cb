// SPDX-License-Identifier: MIT
// EXT_meshopt_compression (a ratified vendor extension of glTF 2.0): bufferViews stored compressed
// by meshoptimizer's codecs in another buffer, as gltfpack -c, -cc and -cf write them. Internal to
// odeskin_gltf; decoding is Debian's meshoptimizer 0.18 (its version 0 bitstreams, which the
// extension specifies). Two steps around tinygltf's load:
//  - before it, the placeholder buffers that stand for the uncompressed data (no uri, or tagged
//    "fallback") become one-byte buffers: tinygltf 2.7 would otherwise copy a GLB's BIN chunk into
//    them, fail looking for a file without a name, or read a fallback file odeskin does not need;
//  - after it, every compressed bufferView is decoded into a buffer of its own and pointed at it,
//    so the accessors read decoded bytes like any others.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

#include <tiny_gltf.h>

#include "../core/status.hpp"

namespace odeskin::gltf {

inline constexpr const char* kMeshoptExtension = "EXT_meshopt_compression";
// The name of the buffers decodeMeshoptViews adds. The limits on what a read may decode
// (DecodeBudget) count the file's own bytes, not these: a few compressed bytes must not buy a
// budget of gigabytes.
inline constexpr const char* kDecodedBufferName = "odeskin: EXT_meshopt_compression, decoded";

// `json` (a .gltf, or a GLB's JSON chunk) with its placeholder buffers replaced, or nullopt when it
// has none: it does not use the extension, or does not parse (tinygltf then says why). In a GLB,
// buffer 0 without a uri is the BIN chunk, not a placeholder. The JSON must have passed the nesting
// check first (the parser recurses); the loader calls this only on JSON that names the extension.
std::optional<std::string> withoutMeshoptPlaceholders(std::string_view json, bool glb);

// Decodes every bufferView with an EXT_meshopt_compression object. `source` names the file in the
// messages. kParseError naming the bufferView for what the extension forbids (a byteStride other
// than the bufferView's, a byteLength other than byteStride x count, a stride, count or filter the
// mode does not allow, an unknown mode or filter), compressed bytes outside their buffer, data that
// does not decode, and decoded data past 16 MiB plus 32 bytes per byte of the file's buffers (a few
// compressed bytes may claim gigabytes); kInvalidArgument for a bufferView compressed with
// KHR_meshopt_compression, whose later bitstreams meshoptimizer 0.18 cannot read.
Status decodeMeshoptViews(tinygltf::Model& model, const std::string& source);

}  // namespace odeskin::gltf
