// SPDX-License-Identifier: MIT
// The shared data's sequences are numbered files (horse-01.obj, cat-09.obj, cheburashka-3): the
// paths of the chosen numbers, for the harness and the report programs alike.
#pragma once

#include <cstdio>
#include <filesystem>
#include <initializer_list>
#include <vector>

namespace odeskin::bench {

// dir / (pattern with %d-style formatting of each number), in the order given.
inline std::vector<std::filesystem::path> numbered(const std::filesystem::path& dir, const char* pattern,
                                                   std::initializer_list<int> numbers) {
  std::vector<std::filesystem::path> paths;
  for (int n : numbers) {
    char name[64];
    std::snprintf(name, sizeof name, pattern, n);
    paths.push_back(dir / name);
  }
  return paths;
}

}  // namespace odeskin::bench
