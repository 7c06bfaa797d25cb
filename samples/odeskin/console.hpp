// SPDX-License-Identifier: MIT
// Where a command writes and how it ends (ECOSYSTEM.md 5a): results on `out`, progress and errors
// on `err`; exit 0 on success, 1 for a bad input file or a runtime failure, 2 for a usage error,
// each failure as one line "odeskin: error: ...".
#pragma once

#include <ostream>
#include <string>

#include "engine/core/status.hpp"

namespace odeskin {

inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;
inline constexpr int kExitUsage = 2;

struct Console {
  std::ostream& out;
  std::ostream& err;
  bool quiet = false;         // --quiet: no summary, no progress, no notes
  bool interactive = false;   // err is a terminal: progress bars may redraw it
};

// Prints "odeskin: error: <message>" and returns `code`.
inline int reportError(Console& console, const std::string& message, int code) {
  console.err << "odeskin: error: " << message << "\n";
  return code;
}
inline int reportFailure(Console& console, const Status& status) {
  return reportError(console, status.message(), kExitFailure);
}
inline int reportUsage(Console& console, const std::string& message) {
  return reportError(console, message, kExitUsage);
}

}  // namespace odeskin
