// SPDX-License-Identifier: MIT
// Reading back the binary files odeskin writes for other tools (PC2, PLY): little-endian values at
// byte offsets, decoded by hand so the tests do not trust the writers' own helpers.
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>
#include <string>

namespace odeskin::testing {

inline std::uint32_t u32At(const std::string& bytes, std::size_t at) {
  std::uint32_t v = 0;
  for (int i = 3; i >= 0; --i) v = (v << 8) | static_cast<std::uint8_t>(bytes[at + static_cast<std::size_t>(i)]);
  return v;
}

inline float f32At(const std::string& bytes, std::size_t at) { return std::bit_cast<float>(u32At(bytes, at)); }

}  // namespace odeskin::testing
