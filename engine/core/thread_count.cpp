// SPDX-License-Identifier: MIT
#include "thread_count.hpp"

#include <algorithm>
#include <cstddef>

#include <tbb/global_control.h>

namespace odeskin {

unsigned allowedThreads() {
  const std::size_t allowed = tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
  return static_cast<unsigned>(std::clamp<std::size_t>(allowed, 1, 1u << 16));
}

unsigned usableThreads(unsigned requested) {
  const unsigned allowed = allowedThreads();
  return requested == 0 ? allowed : std::min(requested, allowed);
}

}  // namespace odeskin
