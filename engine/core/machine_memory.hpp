// SPDX-License-Identifier: MIT
// The machine's memory, for refusing up front what cannot fit. Linux overcommits: a buffer larger
// than the machine is granted, and the out-of-memory killer ends the process (SIGKILL, no message)
// when it is first written, so std::bad_alloc never comes.
#pragma once

#include <cstdint>
#include <string>

namespace odeskin {

// Physical memory in bytes (sysconf), or 0 when the system does not say.
std::uint64_t physicalMemoryBytes();

// "26.2 GiB": sizes in messages that compare a need with physicalMemoryBytes().
std::string gibibytesText(std::uint64_t bytes);

}  // namespace odeskin
