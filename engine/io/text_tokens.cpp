// SPDX-License-Identifier: MIT
#include "text_tokens.hpp"

#include <cmath>

#include "../core/input_file.hpp"

namespace odeskin {

Result<std::string> readTextFile(const std::filesystem::path& path) { return readInputFile(path); }

bool LineReader::next(std::string_view& line) {
  if (pos_ >= text_.size()) return false;
  std::size_t end = text_.find('\n', pos_);
  if (end == std::string::npos) end = text_.size();
  line = std::string_view(text_.data() + pos_, end - pos_);
  pos_ = end + 1;
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
