// SPDX-License-Identifier: MIT
#include "machine_memory.hpp"

#include <unistd.h>

#include "number_text.hpp"

namespace odeskin {

std::uint64_t physicalMemoryBytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES);
  const long page_size = ::sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || page_size <= 0) return 0;
  return static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page_size);
}

std::string gibibytesText(std::uint64_t bytes) {
  std::string text;
  appendNumber(text, static_cast<double>(bytes) / (1024.0 * 1024.0 * 1024.0), 1, std::chars_format::fixed);
  return text + " GiB";
}

Status checkFitsInMemory(std::uint64_t bytes, std::uint64_t memory_bytes, const std::string& what,
                         const std::string& remedy) {
  if (memory_bytes == 0 || bytes <= memory_bytes) return okStatus();
  return outOfRange(what + " need about " + gibibytesText(bytes) + ", more than this machine's " +
                    gibibytesText(memory_bytes) + " of memory; " + remedy);
}

}  // namespace odeskin
