// SPDX-License-Identifier: MIT
// Outputs are written to a temporary file beside their target and renamed into place
// (writeFileAtomically), so a failed write never leaves half a file under the target's name. A
// signal that ends the process during the write would still leave the temporary behind: a 288 MB
// OBJ takes a second to write, and SIGTERM then left a `.tmpNNNNNN` fragment. So every temporary
// is registered while it exists, and a program that ends on SIGINT or SIGTERM calls
// removePendingFiles() from its handler (the odeskin command line does; a host application with
// its own handlers may too).
#pragma once

#include <filesystem>

namespace odeskin {

// Registers `path` for removePendingFiles() for the mark's lifetime. At most kMaxPendingFiles
// paths of up to kMaxPendingPathBytes are held at once; a path beyond either limit is simply not
// registered (the write itself goes ahead).
class PendingFile {
 public:
  explicit PendingFile(const std::filesystem::path& path);
  ~PendingFile();
  PendingFile(const PendingFile&) = delete;
  PendingFile& operator=(const PendingFile&) = delete;

 private:
  int slot_ = -1;
};

inline constexpr int kMaxPendingFiles = 32;
inline constexpr int kMaxPendingPathBytes = 4096;

// Unlinks every registered temporary. Async-signal-safe (atomics and unlink(2) only); a slot
// being registered or released at that moment is left alone, never read half-written.
void removePendingFiles() noexcept;

}  // namespace odeskin
