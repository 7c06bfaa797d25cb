// SPDX-License-Identifier: MIT
// Appending 32-bit values to a byte string in little-endian order, whatever the machine's, for
// the binary formats other tools read (PC2, PLY).
#pragma once

#include <bit>
#include <cstdint>
#include <string>

namespace odeskin {

inline void appendLittleEndianU32(std::string& out, std::uint32_t v) {
  for (int shift = 0; shift < 32; shift += 8) out.push_back(static_cast<char>((v >> shift) & 0xFFU));
}

inline void appendLittleEndianF32(std::string& out, float v) { appendLittleEndianU32(out, std::bit_cast<std::uint32_t>(v)); }

}  // namespace odeskin
