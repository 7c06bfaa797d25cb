// SPDX-License-Identifier: MIT
// Output paths checked before any work. An output must not replace an input (`odeskin fit a.obj
// b.obj -o a.obj` wrote the asset over the first pose), and a file output must not name a folder
// (`fit ... -o out/` fitted, then failed to write and left out/ behind).
#pragma once

#include <filesystem>
#include <span>
#include <string>
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

// "" when `output` can be a file; else why not, for "OPTION PATH: ..." messages.
inline std::string folderNotFile(const std::filesystem::path& output) {
  if (output.empty()) return {};
  std::error_code ec;
  if (!output.has_filename()) return "names a folder (it ends in a separator); give a file name";
  if (std::filesystem::is_directory(output, ec)) return "is a folder; give a file name";
  return {};
}

}  // namespace odeskin
