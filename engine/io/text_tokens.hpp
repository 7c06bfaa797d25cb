// SPDX-License-Identifier: MIT
// Reading line-oriented text formats (OBJ, libigl .tgf/.dmat/.Tmat): the whole file, its lines with
// numbers for error messages, whitespace tokens, and strict number parsing (std::from_chars: no
// locale, no trailing garbage, no NaN or infinity).
#pragma once

#include <charconv>
#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>

#include "../core/result.hpp"

namespace odeskin {

// The file's bytes: readInputFile (engine/core/input_file.hpp), which refuses directories and devices.
Result<std::string> readTextFile(const std::filesystem::path& path);

// The text's lines one by one (LF, CRLF or CR; last line with or without one), numbered from 1,
// after a UTF-8 byte order mark if the text starts with one.
class LineReader {
 public:
  explicit LineReader(const std::string& text);
  bool next(std::string_view& line);
  std::size_t number() const { return number_; }

 private:
  const std::string& text_;
  std::size_t pos_ = 0;
  std::size_t number_ = 0;
};

// Space, tab, CR, VT, FF: what separates tokens (CR too, so CRLF files need no special case).
inline bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

// Next whitespace-separated token of `line` (advanced past it); empty at the end.
std::string_view nextToken(std::string_view& line);

// A finite double, optionally with a leading '+'; false for anything else.
bool parseDouble(std::string_view token, double& out);

// A whole integer token; false for an empty token, trailing characters or overflow.
template <typename Int>
bool parseInt(std::string_view token, Int& out) {
  const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), out);
  return !token.empty() && ec == std::errc() && ptr == token.data() + token.size();
}

}  // namespace odeskin
