// SPDX-License-Identifier: MIT
// Where a JSON parse is, as a path ("curves.a.points[1][0]"), followed through nlohmann's SAX
// events, and the first key an object repeats. JSON allows a repeated key and readers disagree on
// which copy counts (nlohmann keeps the last), so odeskin's own JSON formats refuse it: a pose,
// material or network file that named one field twice was read without a word. glTF is tinygltf's
// to read.
#pragma once

#include <cstddef>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace odeskin {

// "path.key" ("key" at the top level) and "path[i]".
inline std::string jsonChild(const std::string& path, const std::string& key) {
  std::string p = path;
  if (!p.empty()) p.append(1, '.');
  return p.append(key);
}
inline std::string jsonElement(const std::string& path, std::size_t i) {
  std::string p = path;
  return p.append(1, '[').append(std::to_string(i)).append(1, ']');
}

// Every value advances the path; key() stops the parse (false) at the first repeated key of an
// object. Readers derive from it to turn parse errors into messages that name the path.
class JsonPathSax : public nlohmann::json_sax<nlohmann::json> {
 public:
  bool null() override { return next(); }
  bool boolean(bool) override { return next(); }
  bool number_integer(number_integer_t) override { return next(); }
  bool number_unsigned(number_unsigned_t) override { return next(); }
  bool number_float(number_float_t, const string_t&) override { return next(); }
  bool string(string_t&) override { return next(); }
  bool binary(binary_t&) override { return next(); }
  bool start_object(std::size_t) override { return open(false); }
  bool end_object() override { return close(); }
  bool start_array(std::size_t) override { return open(true); }
  bool end_array() override { return close(); }
  bool key(string_t& k) override {
    Level& level = levels_.back();
    level.key = k;
    if (level.keys.insert(k).second) return true;
    repeated_key_ = k;
    return false;
  }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override { return false; }

  // The value being read ("" before the first key of the top-level object).
  std::string path() const { return pathOf(levels_.size()); }
  // The object or array holding it: where a repeated key sits.
  std::string parentPath() const { return levels_.empty() ? std::string() : pathOf(levels_.size() - 1); }
  // The key that stopped the parse, or "".
  const std::string& repeatedKey() const { return repeated_key_; }

 private:
  struct Level {
    bool array = false;
    std::size_t index = 0;
    std::string key;
    std::set<std::string> keys;  // of an object, so far
  };
  bool open(bool array) {
    levels_.push_back({array, 0, {}, {}});
    return true;
  }
  bool close() {
    levels_.pop_back();
    return next();
  }
  bool next() {
    if (!levels_.empty() && levels_.back().array) ++levels_.back().index;
    return true;
  }
  std::string pathOf(std::size_t depth) const {
    std::string p;
    for (std::size_t i = 0; i < depth; ++i) {
      const Level& l = levels_[i];
      if (l.array) p = jsonElement(p, l.index);
      else if (!l.key.empty()) p = jsonChild(p, l.key);
    }
    return p;
  }
  std::vector<Level> levels_;
  std::string repeated_key_;
};

// The first repeated key of `text` as "PATH: \"KEY\" appears twice in one object", or "" when
// there is none or the text is not JSON (the caller's parse reports that). PATH is a.b[2].c.
inline std::string duplicateJsonKey(std::string_view text) {
  JsonPathSax sax;
  nlohmann::json::sax_parse(text, &sax);
  if (sax.repeatedKey().empty()) return {};
  const std::string where = sax.parentPath();
  return (where.empty() ? std::string("(top level)") : where) + ": \"" + sax.repeatedKey() + "\" appears twice in one object";
}

}  // namespace odeskin
