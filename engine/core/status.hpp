// SPDX-License-Identifier: MIT
// Status values instead of exceptions (STYLE.md): every failure a caller or an input file can cause
// comes back as a Status with a code tests can assert and a message that names the culprit.
#pragma once

#include <string>
#include <utility>

namespace odeskin {

enum class StatusCode {
  kOk = 0,
  kInvalidArgument,    // a parameter or span violates its documented contract
  kOutOfRange,         // a value outside the accepted range (N, indices, times)
  kIllPosed,           // the mathematical problem has no unique solution (resonance, rank)
  kDegenerate,         // the problem carries no information (rho = eta = h = 0, L = 0)
  kIoError,            // a file could not be read or written
  kParseError,         // a file was read but its content is malformed
  kUnavailable,        // a runtime resource is missing (no Vulkan device, no layer)
  kDeviceError,        // the Vulkan driver reported a failure
  kInternal,           // a broken invariant inside odeskin
};

const char* statusCodeName(StatusCode code);

// Cheap to pass when ok (empty message); the message is built only on the error path.
class [[nodiscard]] Status {
 public:
  Status() = default;
  Status(StatusCode code, std::string message) : code_(code), message_(std::move(message)) {}

  bool ok() const { return code_ == StatusCode::kOk; }
  StatusCode code() const { return code_; }
  const std::string& message() const { return message_; }
  // "code: message", for logs and the command line.
  std::string toString() const;

 private:
  StatusCode code_ = StatusCode::kOk;
  std::string message_;
};

inline Status okStatus() { return {}; }
Status invalidArgument(std::string message);
Status outOfRange(std::string message);
Status illPosed(std::string message);
Status degenerate(std::string message);
Status ioError(std::string message);
Status parseError(std::string message);
Status unavailable(std::string message);
Status deviceError(std::string message);
Status internalError(std::string message);

}  // namespace odeskin

#define ODESKIN_CONCAT_INNER(a, b) a##b
#define ODESKIN_CONCAT(a, b) ODESKIN_CONCAT_INNER(a, b)

// Returns from the enclosing function when `expr` (a Status) is not ok.
#define ODESKIN_TRY(expr)                                        \
  do {                                                           \
    ::odeskin::Status odeskin_try_status_ = (expr);              \
    if (!odeskin_try_status_.ok()) return odeskin_try_status_;   \
  } while (false)
