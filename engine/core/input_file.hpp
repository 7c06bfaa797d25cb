// SPDX-License-Identifier: MIT
// The one way odeskin reads an input file whole (OBJ, libigl files, .odsk, JSON): regular files,
// and pipes up to kMaxPipeBytes (process substitution, /dev/stdin from a pipe). A directory or a
// device is refused before any read: a .obj that linked to /dev/zero was read until memory ran out
// (4 GB in 10 s). glTF keeps its stricter rule (engine/io/gltf_load.cpp: regular files only).
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>

#include "result.hpp"

namespace odeskin {

inline constexpr std::size_t kMaxPipeBytes = std::size_t{1} << 30;

// The file's bytes. kIoError naming the path: "cannot open for reading", "is a directory, not a
// file", "is a device, not a file", "more than N bytes from a pipe", "read failed".
Result<std::string> readInputFile(const std::filesystem::path& path, std::size_t max_pipe_bytes = kMaxPipeBytes);

}  // namespace odeskin
