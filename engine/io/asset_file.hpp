// SPDX-License-Identifier: MIT
// The .odsk asset: a versioned little-endian binary file holding a DeformAsset.
//   header (32 bytes): magic "ODSK\r\n\x1a\n", u32 version, u32 flags (0), u64 payload bytes,
//                      u64 FNV-1a 64 checksum of the payload
//   payload: tagged sections (u32 tag, u64 bytes, data) so later versions can add sections;
//            readers skip tags they do not know. Version 1 writes (and requires) META REST FACE
//            RNDR BIND CURV CMAT MATL INFL BONE KEYS SEGM, tags being the four ASCII letters,
//            and, when the asset has them, RNRM (the render layout's bind normals), RUV0 (its
//            TEXCOORD_0), RPRM (its glTF primitives: face runs and material indices) and ROBJ
//            (empty: the layout came from an OBJ's corners, RenderLayout::obj_order).
// Doubles are stored bit-exactly: save -> load reproduces the asset exactly.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include "../core/result.hpp"
#include "../offline/deform_asset.hpp"

namespace odeskin {

inline constexpr std::uint32_t kAssetVersion = 1;

// The whole file as bytes (validateDeformAsset first: kInvalidArgument for an inconsistent asset).
Result<std::string> encodeAsset(const DeformAsset& asset);
// kParseError naming `source` for a bad magic, an unknown version, a size or checksum mismatch
// (truncated or corrupted), a section that overruns; then validateDeformAsset's errors.
Result<DeformAsset> decodeAsset(const std::string& bytes, const std::string& source);

// Atomic write (temp + rename): no half-written asset on failure. kIoError naming the path.
Status saveAsset(const std::filesystem::path& path, const DeformAsset& asset);
// kIoError naming the path when it cannot be read; then decodeAsset's errors with source = path.
Result<DeformAsset> loadAsset(const std::filesystem::path& path);

// FNV-1a 64 of the payload (what the header stores), for tools and tests that build files.
std::uint64_t assetChecksum(std::string_view payload);

}  // namespace odeskin
