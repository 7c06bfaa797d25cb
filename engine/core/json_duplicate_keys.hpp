// SPDX-License-Identifier: MIT
// JSON allows an object to repeat a key, and readers disagree on which copy counts (nlohmann keeps
// the last): a pose or material file that named one field twice was read without a word. odeskin's
// own JSON formats refuse such files, naming the key and where it is (the network reader does the
// same in its own path-tracking parse). glTF is tinygltf's to read.
#pragma once

#include <set>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace odeskin {

// The first repeated key of `text` as "PATH: \"KEY\" appears twice in one object", or "" when
// there is none or the text is not JSON (the caller's parse reports that). PATH is a.b[2].c.
inline std::string duplicateJsonKey(std::string_view text) {
  using Json = nlohmann::json;
  class Keys : public nlohmann::json_sax<Json> {
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
      found_ = (path().empty() ? std::string("(top level)") : path()) + ": \"" + k + "\" appears twice in one object";
      return false;
    }
    bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override { return false; }
    const std::string& found() const { return found_; }

   private:
    struct Level {
      bool array = false;
      std::size_t index = 0;
      std::string key;
      std::set<std::string> keys;
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
    // The path of the object being read, not of the repeated key itself.
    std::string path() const {
      std::string p;
      for (std::size_t i = 0; i + 1 < levels_.size(); ++i) {
        const Level& l = levels_[i];
        if (l.array) {
          p.append(1, '[').append(std::to_string(l.index)).append(1, ']');
        } else {
          if (!p.empty()) p.append(1, '.');
          p.append(l.key);
        }
      }
      return p;
    }
    std::vector<Level> levels_;
    std::string found_;
  };
  Keys keys;
  Json::sax_parse(text, &keys);
  return keys.found();
}

}  // namespace odeskin
