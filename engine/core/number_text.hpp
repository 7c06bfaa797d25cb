// SPDX-License-Identifier: MIT
// Numbers in error messages. std::to_string writes "%f": a weight of -1e-9 read "-0.000000 < 0",
// a rank test's 1e-17 read "0.000000", and 1e308 took 309 digits.
#pragma once

#include <cstdio>
#include <string>

namespace odeskin {

// "%.9g": short, and enough digits to tell a sum of 1.000001 from 1; nan and inf as C prints them.
inline std::string messageNumber(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", x);
  return text;
}

}  // namespace odeskin
