// SPDX-License-Identifier: MIT
#include "pending_files.hpp"

#include <unistd.h>

#include <array>
#include <atomic>
#include <cstring>
#include <string>
#include <system_error>

namespace odeskin {
namespace {

// A slot's path is written by its owner only while the slot is kClaimed and read by
// removePendingFiles() only after it moved the slot from kHeld to kRemoving, so no path is read
// while it is being overwritten. The remover leaves the slot kRemoved; only the owner frees it,
// so a slot is never handed to a new file while an old mark still names it.
enum SlotState : int { kFree, kClaimed, kHeld, kRemoving, kRemoved };

struct Slot {
  std::atomic<int> state{kFree};
  std::array<char, kMaxPendingPathBytes> path{};
};

std::array<Slot, kMaxPendingFiles> g_slots;

static_assert(std::atomic<int>::is_always_lock_free, "the signal handler needs lock-free atomics");

}  // namespace

PendingFile::PendingFile(const std::filesystem::path& path) {
  // Absolute: a handler may run after another thread of the host changed directory.
  std::error_code ec;
  const std::filesystem::path absolute = std::filesystem::absolute(path, ec);
  if (ec) return;
  const std::string& text = absolute.native();
  if (text.size() >= static_cast<std::size_t>(kMaxPendingPathBytes)) return;
  for (int s = 0; s < kMaxPendingFiles; ++s) {
    int expected = kFree;
    if (!g_slots[s].state.compare_exchange_strong(expected, kClaimed, std::memory_order_acquire)) continue;
    std::memcpy(g_slots[s].path.data(), text.c_str(), text.size() + 1);
    g_slots[s].state.store(kHeld, std::memory_order_release);
    slot_ = s;
    return;
  }
}

PendingFile::~PendingFile() {
  if (slot_ < 0) return;
  std::atomic<int>& state = g_slots[slot_].state;
  int expected = kHeld;
  if (state.compare_exchange_strong(expected, kFree, std::memory_order_acq_rel)) return;
  // Removed, or being removed by a handler on another thread (one on this thread has finished
  // before this code runs again): wait for the unlink before the slot can be reused.
  while (state.load(std::memory_order_acquire) != kRemoved) {
  }
  state.store(kFree, std::memory_order_release);
}

void removePendingFiles() noexcept {
  for (Slot& slot : g_slots) {
    int expected = kHeld;
    if (!slot.state.compare_exchange_strong(expected, kRemoving, std::memory_order_acq_rel)) continue;
    ::unlink(slot.path.data());
    slot.state.store(kRemoved, std::memory_order_release);
  }
}

}  // namespace odeskin
