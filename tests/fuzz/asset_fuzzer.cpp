// SPDX-License-Identifier: MIT
// libFuzzer target: the .odsk asset reader (engine/io/asset_file.hpp) on arbitrary bytes. Each
// input is decoded as it is, then again with the header's payload size and checksum made to match
// (else nearly every mutation of the payload would stop at the checksum and the section parsers
// behind it would never be reached). An accepted asset must encode back to a file that decodes to
// the same bytes, and must play: validateDeformAsset is what keeps the player in bounds. The
// runtime must build its asset (packing, corners, hard edges) from it or refuse it.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

#include "engine/io/asset_file.hpp"
#include "engine/offline/deform_player.hpp"
#include "engine/runtime/runtime_asset.hpp"
#include "fuzz_checks.hpp"

namespace {

using namespace odeskin;

constexpr std::size_t kHeaderBytes = 32;

void check(const std::string& bytes) {
  const std::string source = "fuzz.odsk";
  const Result<DeformAsset> asset = decodeAsset(bytes, source);
  if (!fuzz::accepted(asset, source)) return;
  const Result<std::string> encoded = encodeAsset(*asset);
  fuzz::require(encoded.ok(), "a decoded asset does not encode: " + encoded.status().toString());
  const Result<DeformAsset> again = decodeAsset(*encoded, source);
  fuzz::require(again.ok(), "an encoded asset does not decode: " + again.status().toString());
  const Result<std::string> reencoded = encodeAsset(*again);
  fuzz::require(reencoded.ok() && *reencoded == *encoded, "encode(decode(encode(asset))) differs");

  // The runtime's packing, time bases and render corners (hard edges from the asset's normals)
  // must accept or refuse it, never crash.
  (void)RuntimeAsset::create(*asset);

  const Result<DeformPlayer> player = DeformPlayer::create(*asset);
  if (!player.ok()) return;  // e.g. a material whose time basis has no solution: refused, not played
  std::vector<Vec3> out(asset->vertexCount());
  for (std::uint32_t segment = 0; segment < player->segmentCount() && segment < 4; ++segment) {
    (void)player->play(*asset, segment, 0.5, out);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string bytes = fuzz::text(data, size);
  check(bytes);
  if (bytes.size() >= kHeaderBytes) {
    const std::uint64_t payload = bytes.size() - kHeaderBytes;
    const std::uint64_t checksum = assetChecksum(std::string_view(bytes).substr(kHeaderBytes));
    // Little-endian, as the format stores them (x86-64 and every target odeskin builds for).
    std::memcpy(bytes.data() + 16, &payload, 8);
    std::memcpy(bytes.data() + 24, &checksum, 8);
    check(bytes);
  }
  return 0;
}
