// SPDX-License-Identifier: MIT
// main() of the small programs (bench/ reports, the blending samples): what their option parsing
// (CLI11) or the standard library throws becomes one line and exit status 1, not an abort.
#pragma once

#include <cstdio>
#include <exception>

namespace odeskin {

inline int runGuarded(const char* program, int (*run)(int, char**), int argc, char** argv) noexcept {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: error: %s\n", program, e.what());
  } catch (...) {
    std::fprintf(stderr, "%s: error: an unknown exception\n", program);
  }
  return 1;
}

}  // namespace odeskin
