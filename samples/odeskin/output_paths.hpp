// SPDX-License-Identifier: MIT
// Output paths checked before any work. An output must not replace an input (`odeskin fit a.obj
// b.obj -o a.obj` wrote the asset over the first pose), and a file output must not name a folder
// (`fit ... -o out/` fitted, then failed to write and left out/ behind). And the folder an output
// goes in, made when it is written. And the outputs of a command that fails part way, removed again.
#pragma once

#include <filesystem>
#include <span>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "engine/core/status.hpp"

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

// The file a write to `output` lands in: writes go through symbolic links, a dangling one too.
inline std::filesystem::path writtenFile(std::filesystem::path output) {
  std::error_code ec;
  for (int hop = 0; hop < 40 && std::filesystem::is_symlink(output, ec); ++hop) {
    const std::filesystem::path target = std::filesystem::read_symlink(output, ec);
    if (ec) break;
    output = target.is_absolute() ? target : output.parent_path() / target;
  }
  const std::filesystem::path resolved = std::filesystem::weakly_canonical(output, ec);
  return ec ? output.lexically_normal() : resolved;
}

// Whether two outputs of one command would be written to one file, the second over the first
// (`rig -o a.tgf --weights a.dmat` with a.dmat a link to a.tgf left the weights in a.tgf).
inline bool sameOutputFile(const std::filesystem::path& a, const std::filesystem::path& b) {
  if (a.empty() || b.empty()) return false;
  std::error_code ec;
  return writtenFile(a) == writtenFile(b) || (std::filesystem::equivalent(a, b, ec) && !ec);
}

// "" when `output` can be a file; else why not, for "OPTION PATH: ..." messages.
inline std::string folderNotFile(const std::filesystem::path& output) {
  if (output.empty()) return {};
  std::error_code ec;
  if (!output.has_filename()) return "names a folder (it ends in a separator); give a file name";
  if (std::filesystem::is_directory(output, ec)) return "is a folder; give a file name";
  return {};
}

// Creates the folder `file` goes in, with its parents; ok when there is none to create. kIoError
// "FOLDER: cannot create directory: WHY" when it cannot be made.
inline Status createParentFolder(const std::filesystem::path& file) {
  const std::filesystem::path parent = file.parent_path();
  if (parent.empty()) return okStatus();
  std::error_code ec;
  std::filesystem::create_directories(parent, ec);
  if (ec) return ioError(parent.string() + ": cannot create directory: " + ec.message());
  return okStatus();
}

// The files a command has written so far. When a later output fails, undo() removes them, so a
// failed command leaves none of its outputs (each file is already written atomically; this makes
// the set of them all or nothing). Only regular files go: an output that is a device or FIFO
// (written in place) stays.
class WrittenOutputs {
 public:
  void add(std::filesystem::path file) { files_.push_back(std::move(file)); }
  void removeAll() {
    std::error_code ec;
    for (const std::filesystem::path& file : files_) {
      if (std::filesystem::is_regular_file(std::filesystem::status(file, ec))) std::filesystem::remove(file, ec);
    }
    files_.clear();
  }
  // removeAll(), handing `failure` back: `return written.undo(s);`.
  Status undo(Status failure) {
    removeAll();
    return failure;
  }

 private:
  std::vector<std::filesystem::path> files_;
};

}  // namespace odeskin
