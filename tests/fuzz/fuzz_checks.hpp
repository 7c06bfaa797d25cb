// SPDX-License-Identifier: MIT
// What every fuzz target asserts beyond "no crash": a refused input is a Status whose message
// starts with the name the reader was given (errors name the file), and an accepted one keeps the
// reader's documented invariants. A broken promise aborts, which libFuzzer reports as a finding.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "engine/core/result.hpp"
#include "engine/core/status.hpp"
#include "engine/core/types.hpp"

namespace odeskin::fuzz {

[[noreturn]] inline void fail(const std::string& what) {
  std::fprintf(stderr, "odeskin fuzz: %s\n", what.c_str());
  std::abort();
}

inline void require(bool condition, const std::string& what) {
  if (!condition) fail(what);
}

// A refusal: not kOk, not an internal error, and its message starts with `source`.
inline void requireNamedError(const Status& status, const std::string& source) {
  require(!status.ok(), "an error result carries kOk");
  require(status.code() != StatusCode::kInternal, "bad input reported as an internal error: " + status.toString());
  require(status.message().rfind(source, 0) == 0, "error does not start with '" + source + "': " + status.toString());
}

// Whether a reader accepted its input; a refusal must be a named error (above).
template <typename T>
bool accepted(const Result<T>& result, const std::string& source) {
  if (result.ok()) return true;
  requireNamedError(result.status(), source);
  return false;
}

// Every coordinate finite.
inline bool finite(const Vec3& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

// libFuzzer's bytes as the text a reader parses.
inline std::string text(const std::uint8_t* data, std::size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

}  // namespace odeskin::fuzz
