// SPDX-License-Identifier: MIT
// The machine's memory, for refusing up front what cannot fit. Linux overcommits: a buffer larger
// than the machine is granted, and the out-of-memory killer ends the process (SIGKILL, no message)
// when it is first written, so std::bad_alloc never comes.
#pragma once

#include <cstdint>
#include <string>

#include "result.hpp"

namespace odeskin {

// Physical memory in bytes (sysconf), or 0 when the system does not say.
std::uint64_t physicalMemoryBytes();

// "26.2 GiB".
std::string gibibytesText(std::uint64_t bytes);

// kOutOfRange "<what> need about X GiB, more than this machine's Y GiB of memory; <remedy>" when
// `bytes` > `memory_bytes` (physicalMemoryBytes(), or a test's; 0: unknown, then it fits).
Status checkFitsInMemory(std::uint64_t bytes, std::uint64_t memory_bytes, const std::string& what,
                         const std::string& remedy);

}  // namespace odeskin
