// SPDX-License-Identifier: MIT
// Counts the program's calls of the global operator new (allocation_counter.cpp replaces every
// form of it, so link that file into one test executable only). The soak tests read the count
// around the frames they play to show that the runtime allocates nothing per frame. malloc calls
// from C code (TBB's own pools, the Vulkan driver) are not counted; the resident set covers those.
#pragma once

#include <cstddef>
#include <cstdint>

namespace odeskin::testing {

struct AllocationCount {
  std::uint64_t calls = 0;
  std::uint64_t bytes = 0;
};

// Totals since the program started, over every thread.
AllocationCount allocationsSoFar();

}  // namespace odeskin::testing
