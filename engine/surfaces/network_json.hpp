// SPDX-License-Identifier: MIT
// Patch networks as JSON files (docs/surfaces.md, "C2 surface patches", has the schema and
// examples). Every error names the field as a path into the file, e.g.
// "boundaries[1].derivatives.at[0]: 1.5 is outside (0, 1)", and a file's errors start with its path.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "../core/result.hpp"
#include "network.hpp"

namespace odeskin {

inline constexpr int kNetworkJsonVersion = 1;
// Most patches (rows x columns) a network file may describe: 4M, four times the 1000 x 1000 network
// of docs/surfaces.md. More could never be tessellated within kMaxTessellationVertices at the
// default 33 x 33 samples, and the description alone would take hundreds of megabytes.
inline constexpr std::uint64_t kMaxNetworkPatches = std::uint64_t{1} << 22;

// kParseError for malformed JSON (with line, column and the path reached), missing or unknown
// fields, wrong types, non-finite numbers, unknown curve names and out-of-range indices.
Result<NetworkDescription> parseNetworkDescription(std::string_view text);

// As parseNetworkDescription, and kIoError when the file cannot be read; messages start with `path`.
Result<NetworkDescription> readNetworkDescription(const std::filesystem::path& path);

// readNetworkDescription, then Network::build (its errors prefixed with `path`).
Result<Network> loadNetwork(const std::filesystem::path& path, std::vector<std::string>* warnings = nullptr);

// The description as a version-1 network file (shapes written per patch only where they differ
// from the first patch's). parseNetworkDescription reads it back unchanged.
std::string networkJson(const NetworkDescription& description);

}  // namespace odeskin
