// SPDX-License-Identifier: MIT
// What a program printed but never reached standard output (a full disk, a closed descriptor, a
// pipe nobody reads) fails a run that succeeded, as coreutils treat it: `odeskin info a.odsk >
// /dev/full` exited 0 with nothing written. Shared by the sample programs' main().
#pragma once

#include <cerrno>
#include <cstdio>
#include <string.h>  // GNU strerror_r

namespace odeskin {

// Flushes stdout and returns `code`, or 1 (when `code` was 0) after one line on stderr
// "<prefix><verb>: standard output: write failed: <cause>" (no "<verb>: " when `verb` is empty).
// Allocates nothing: it also runs after a std::bad_alloc.
inline int checkStandardOutput(const char* prefix, const char* verb, int code) noexcept {
  errno = 0;
  if (std::fflush(stdout) == 0 && !std::ferror(stdout)) return code;
  const int error = errno;
  char buffer[128];
  const char* cause = error != 0 ? ::strerror_r(error, buffer, sizeof buffer) : "";  // GNU: returns the text
  std::fprintf(stderr, "%s%s%sstandard output: write failed%s%s\n", prefix, verb, *verb != '\0' ? ": " : "",
               error != 0 ? ": " : "", cause);
  return code == 0 ? 1 : code;
}

}  // namespace odeskin
