// SPDX-License-Identifier: MIT
#include "status.hpp"

namespace odeskin {

const char* statusCodeName(StatusCode code) {
  switch (code) {
    case StatusCode::kOk: return "ok";
    case StatusCode::kInvalidArgument: return "invalid argument";
    case StatusCode::kOutOfRange: return "out of range";
    case StatusCode::kIllPosed: return "ill-posed";
    case StatusCode::kDegenerate: return "degenerate";
    case StatusCode::kIoError: return "i/o error";
    case StatusCode::kParseError: return "parse error";
    case StatusCode::kUnavailable: return "unavailable";
    case StatusCode::kDeviceError: return "device error";
    case StatusCode::kInternal: return "internal error";
  }
  return "unknown";
}

std::string Status::toString() const {
  if (ok()) return "ok";
  return std::string(statusCodeName(code_)) + ": " + message_;
}

Status invalidArgument(std::string message) { return {StatusCode::kInvalidArgument, std::move(message)}; }
Status outOfRange(std::string message) { return {StatusCode::kOutOfRange, std::move(message)}; }
Status illPosed(std::string message) { return {StatusCode::kIllPosed, std::move(message)}; }
Status degenerate(std::string message) { return {StatusCode::kDegenerate, std::move(message)}; }
Status ioError(std::string message) { return {StatusCode::kIoError, std::move(message)}; }
Status parseError(std::string message) { return {StatusCode::kParseError, std::move(message)}; }
Status unavailable(std::string message) { return {StatusCode::kUnavailable, std::move(message)}; }
Status deviceError(std::string message) { return {StatusCode::kDeviceError, std::move(message)}; }
Status internalError(std::string message) { return {StatusCode::kInternal, std::move(message)}; }

}  // namespace odeskin
