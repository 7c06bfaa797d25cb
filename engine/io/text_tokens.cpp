// SPDX-License-Identifier: MIT
#include "text_tokens.hpp"

#include <cmath>

#include "../core/input_file.hpp"

namespace odeskin {

Result<std::string> readTextFile(const std::filesystem::path& path) { return readInputFile(path); }

LineReader::LineReader(const std::string& text) : text_(text) {
  // A UTF-8 byte order mark (Windows editors write one) made the first line an unknown statement:
  // an OBJ lost its first vertex and every face then named the wrong vertices.
  if (text_.starts_with("\xEF\xBB\xBF")) pos_ = 3;
}

bool LineReader::next(std::string_view& line) {
  if (pos_ >= text_.size()) return false;
  // LF, CRLF or a lone CR (classic Mac OS): a file of CR-only lines read as one line ("no faces").
  std::size_t end = text_.find_first_of("\r\n", pos_);
  if (end == std::string::npos) end = text_.size();
  line = std::string_view(text_.data() + pos_, end - pos_);
  pos_ = end + (end + 1 < text_.size() && text_[end] == '\r' && text_[end + 1] == '\n' ? 2 : 1);
  ++number_;
  return true;
}

std::string_view nextToken(std::string_view& line) {
  while (!line.empty() && isSpace(line.front())) line.remove_prefix(1);
  std::size_t end = 0;
  while (end < line.size() && !isSpace(line[end])) ++end;
  const std::string_view token = line.substr(0, end);
  line.remove_prefix(end);
  return token;
}

bool parseDouble(std::string_view token, double& out) {
  const char* first = token.data();
  const char* last = token.data() + token.size();
  if (first != last && *first == '+') ++first;
  const auto [ptr, ec] = std::from_chars(first, last, out);
  return first != last && ec == std::errc() && ptr == last && std::isfinite(out);
}

}  // namespace odeskin
