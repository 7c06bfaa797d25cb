// SPDX-License-Identifier: MIT
// An output must not replace an input: `odeskin fit a.obj b.obj -o a.obj` wrote the asset over the
// first pose. Each verb checks its outputs against its inputs before it reads anything.
#pragma once

#include <filesystem>
#include <span>
#include <system_error>

namespace odeskin {

// Whether writing `output` would replace one of `inputs`: the same name once normalised, or, when
// both exist, the same file (another spelling of the path, a symbolic or hard link).
inline bool overwritesInput(const std::filesystem::path& output, std::span<const std::filesystem::path> inputs) {
  if (output.empty()) return false;
  for (const std::filesystem::path& input : inputs) {
    if (input.empty()) continue;
    if (output.lexically_normal() == input.lexically_normal()) return true;
    std::error_code ec;
    if (std::filesystem::equivalent(output, input, ec) && !ec) return true;
  }
  return false;
}

}  // namespace odeskin
