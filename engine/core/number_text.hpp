// SPDX-License-Identifier: MIT
// How odeskin prints numbers in summaries and messages: short and locale-independent.
// std::to_string writes "%f": a weight of -1e-9 read "-0.000000 < 0", a rank test's 1e-17 read
// "0.000000", and 1e308 took 309 digits.
#pragma once

#include <cstdio>
#include <string>

namespace odeskin {

namespace number_text_detail {
inline std::string formatted(const char* format, double x) {
  char text[32];
  std::snprintf(text, sizeof text, format, x);
  return text;
}
}  // namespace number_text_detail

// "1.23e-04": errors and tolerances, whose magnitude is what matters.
inline std::string scientific(double x) { return number_text_detail::formatted("%.2e", x); }

// "%g": times, sizes and option values as the user typed them.
inline std::string numberText(double x) { return number_text_detail::formatted("%g", x); }

// "%.9g", for values in error messages: enough digits to tell a sum of 1.000001 from 1.
inline std::string messageNumber(double x) { return number_text_detail::formatted("%.9g", x); }

}  // namespace odeskin
