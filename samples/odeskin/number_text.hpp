// SPDX-License-Identifier: MIT
// How the commands print numbers in summaries and messages: short and locale-independent.
#pragma once

#include <cstdio>
#include <string>

namespace odeskin {

// "1.23e-04": errors and tolerances, whose magnitude is what matters.
inline std::string scientific(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2e", x);
  return text;
}

// "%g": times, sizes and option values as the user typed them.
inline std::string numberText(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", x);
  return text;
}

}  // namespace odeskin
