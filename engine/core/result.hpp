// SPDX-License-Identifier: MIT
// Result<T>: a value or a non-ok Status (C++20 has no std::expected).
#pragma once

#include <cassert>
#include <optional>
#include <utility>

#include "status.hpp"

namespace odeskin {

template <typename T>
class [[nodiscard]] Result {
 public:
  Result(T value) : value_(std::move(value)) {}  // cppcheck-suppress noExplicitConstructor ; NOLINT: implicit by design
  Result(Status status) : status_(std::move(status)) {  // cppcheck-suppress noExplicitConstructor ; NOLINT: implicit by design
    assert(!status_.ok() && "a Result built from a Status must carry an error");
  }

  bool ok() const { return value_.has_value(); }
  const Status& status() const { return status_; }

  T& value() & { assert(ok()); return *value_; }
  const T& value() const& { assert(ok()); return *value_; }
  T&& value() && { assert(ok()); return std::move(*value_); }
  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }
  T& operator*() & { return value(); }
  const T& operator*() const& { return value(); }

 private:
  Status status_;
  std::optional<T> value_;
};

}  // namespace odeskin

// Declares `lhs` from a Result expression, or returns its Status from the enclosing function.
#define ODESKIN_ASSIGN_OR_RETURN(lhs, expr)                                          \
  auto ODESKIN_CONCAT(odeskin_result_, __LINE__) = (expr);                           \
  if (!ODESKIN_CONCAT(odeskin_result_, __LINE__).ok())                               \
    return ODESKIN_CONCAT(odeskin_result_, __LINE__).status();                       \
  lhs = std::move(ODESKIN_CONCAT(odeskin_result_, __LINE__)).value()  // NOLINT(bugprone-macro-parentheses): lhs declares
