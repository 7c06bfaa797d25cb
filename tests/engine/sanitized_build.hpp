// SPDX-License-Identifier: MIT
// Whether this test binary runs under a sanitizer. Their runtimes reserve terabytes of address
// space up front, so a test that sets RLIMIT_AS to run out of memory cannot run there.
#pragma once

namespace odeskin::testing {

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
inline constexpr bool kSanitized = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) || __has_feature(memory_sanitizer)
inline constexpr bool kSanitized = true;
#else
inline constexpr bool kSanitized = false;
#endif
#else
inline constexpr bool kSanitized = false;
#endif

}  // namespace odeskin::testing
