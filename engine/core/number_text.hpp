// SPDX-License-Identifier: MIT
// How odeskin prints numbers, in messages and in the files it writes, and reads them from option
// values: short and independent of the C locale. std::to_string writes "%f": a weight of -1e-9 read "-0.000000 < 0", a rank test's 1e-17
// read "0.000000", and 1e308 took 309 digits. snprintf follows LC_NUMERIC: an application that set
// a German locale got OBJ vertices written "v 1,5 2 0", which no reader takes. std::to_chars
// gives printf's "C" output whatever the locale.
#pragma once

#include <algorithm>
#include <charconv>
#include <cmath>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

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

// The finite number all of `text` spells in the "C" locale: an optional sign, then decimal or
// scientific notation. std::stod and operator>> read a denormal such as 1e-320 as a range error,
// and stod follows LC_NUMERIC and takes hexadecimal; neither is wanted for an option's value.
// Hexadecimal, inf, nan, spaces and magnitudes past double's range give nullopt.
inline std::optional<double> finiteNumberIn(std::string_view text) {
  if (text.size() > 1 && text.front() == '+' && text[1] != '-' && text[1] != '+') text.remove_prefix(1);
  double value = 0.0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (ec != std::errc() || ptr != end || !std::isfinite(value)) return std::nullopt;
  return value;
}

// Exactly `count` comma-separated numbers, each as finiteNumberIn reads it ("1,3,0.5").
inline std::optional<std::vector<double>> finiteNumbersIn(std::string_view text, std::size_t count) {
  std::vector<double> values;
  for (std::size_t start = 0;;) {
    const std::size_t end = std::min(text.find(',', start), text.size());
    const std::optional<double> value = finiteNumberIn(text.substr(start, end - start));
    if (!value) return std::nullopt;
    values.push_back(*value);
    if (end == text.size()) break;
    start = end + 1;
  }
  if (values.size() != count) return std::nullopt;
  return values;
}

}  // namespace odeskin
