// SPDX-License-Identifier: MIT
// How odeskin prints numbers, in messages and in the files it writes: short and independent of the
// C locale. std::to_string writes "%f": a weight of -1e-9 read "-0.000000 < 0", a rank test's 1e-17
// read "0.000000", and 1e308 took 309 digits. snprintf follows LC_NUMERIC: an application that set
// a German locale got OBJ vertices written "v 1,5 2 0", which no reader takes. std::to_chars
// gives printf's "C" output whatever the locale.
#pragma once

#include <charconv>
#include <string>
#include <system_error>

namespace odeskin {

// Appends x as printf's "%.{precision}g" (general) or "%.{precision}e" (scientific) in the "C"
// locale would.
inline void appendNumber(std::string& out, double x, int precision,
                         std::chars_format format = std::chars_format::general) {
  char text[48];
  const auto [end, ec] = std::to_chars(text, text + sizeof text, x, format, precision);
  out.append(text, ec == std::errc() ? end : text);
}

namespace number_text_detail {
inline std::string formatted(double x, int precision, std::chars_format format) {
  std::string text;
  appendNumber(text, x, precision, format);
  return text;
}
}  // namespace number_text_detail

// "1.23e-04": errors and tolerances, whose magnitude is what matters.
inline std::string scientific(double x) { return number_text_detail::formatted(x, 2, std::chars_format::scientific); }

// "%g": times, sizes and option values as the user typed them.
inline std::string numberText(double x) { return number_text_detail::formatted(x, 6, std::chars_format::general); }

// "%.{decimals}f": angles and other values read in a fixed unit ("0.42 degrees").
inline std::string fixedText(double x, int decimals) {
  return number_text_detail::formatted(x, decimals, std::chars_format::fixed);
}

// "1.23%": a fraction (0.0123) as a percentage to 3 significant digits, as errors over the box are read.
inline std::string percentText(double fraction) {
  return number_text_detail::formatted(100.0 * fraction, 3, std::chars_format::general) + "%";
}

// The shortest text that reads back as x exactly, for values compared against a bound: nine
// digits print a value one ulp past the bound as the bound itself.
inline std::string exactText(double x) {
  char text[32];  // to_chars's shortest double is at most 24 characters
  const auto [end, ec] = std::to_chars(text, text + sizeof text, x);
  return std::string(text, ec == std::errc() ? end : text);
}

// "%.9g", for values in error messages: enough digits to tell a sum of 1.000001 from 1.
inline std::string messageNumber(double x) { return number_text_detail::formatted(x, 9, std::chars_format::general); }

}  // namespace odeskin
