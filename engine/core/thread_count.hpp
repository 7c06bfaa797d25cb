// SPDX-License-Identifier: MIT
// Thread counts as TBB will run them. TBB runs no more threads at once than the machine has (its
// affinity mask) or a tbb::global_control allows; an arena asked for more gets empty slots, not
// workers, and TBB prints its own warning for large requests. So every thread count the engine
// takes is capped here, and reports give the count that runs. TBB stays out of this header.
#pragma once

namespace odeskin {

// The threads TBB runs at once now: the machine's, or what a tbb::global_control allows (>= 1).
unsigned allowedThreads();

// A requested thread count (0: all) as TBB will run it: min(requested, allowedThreads()).
unsigned usableThreads(unsigned requested);

}  // namespace odeskin
