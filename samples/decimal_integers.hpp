// SPDX-License-Identifier: MIT
// CLI11 2.1 reads integer options with strtoll's base 0, so `--terms 010` was 8 and `--terms 0x10`
// 16, exit 0. Users mean decimal: leading zeros are dropped, other bases refused. Shared by the
// sample programs' option wiring.
#pragma once

#include <cstddef>
#include <string>

#include <CLI/CLI.hpp>

namespace odeskin {

// "[+-]digits" with the leading zeros dropped ("007" -> "7", "-0" stays), or an error naming the text.
inline std::string decimalIntegerProblem(std::string& text) {
  const std::size_t digits = text.empty() || (text[0] != '+' && text[0] != '-') ? 0 : 1;
  const bool decimal = text.size() > digits && text.find_first_not_of("0123456789", digits) == std::string::npos;
  if (!decimal) return "Value " + text + " is not a decimal integer";
  const std::size_t first = text.find_first_not_of('0', digits);
  text.erase(digits, (first == std::string::npos ? text.size() - 1 : first) - digits);
  return std::string();
}

// Puts the decimal check first on every integer option of `app` and its subcommands (CLI11 names
// their types INT and UINT, vectors of them included); call it once every option is added.
inline void requireDecimalIntegers(CLI::App& app) {
  for (CLI::Option* option : app.get_options()) {
    const std::string full = option->get_type_name();  // "INT:<each validator's description>"
    const std::string type = full.substr(0, full.find(':'));
    if (type == "INT" || type == "UINT") option->transform(CLI::Validator(decimalIntegerProblem, "", "DECIMAL"));
  }
  for (CLI::App* sub : app.get_subcommands({})) requireDecimalIntegers(*sub);
}

}  // namespace odeskin
