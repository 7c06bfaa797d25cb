// SPDX-License-Identifier: MIT
#include "worker_arena.hpp"
#include "../core/parallel.hpp"
#include "../core/thread_count.hpp"

#include <algorithm>

#include <tbb/blocked_range.h>
#include <tbb/task_arena.h>

namespace odeskin {

struct WorkerArena::Impl {
  explicit Impl(unsigned threads)
      : arena(threads == 0 ? tbb::task_arena::automatic : static_cast<int>(usableThreads(threads))) {}
  tbb::task_arena arena;
};

WorkerArena::WorkerArena(unsigned threads) : impl_(std::make_unique<Impl>(threads)) {}
WorkerArena::WorkerArena(WorkerArena&&) noexcept = default;
WorkerArena& WorkerArena::operator=(WorkerArena&&) noexcept = default;
WorkerArena::~WorkerArena() = default;

unsigned WorkerArena::threads() const { return static_cast<unsigned>(impl_->arena.max_concurrency()); }

void WorkerArena::run(std::size_t count, std::size_t grain, Chunk chunk, const void* context) const {
  grain = std::max<std::size_t>(grain, 1);
  if (count == 0) return;
  // One thread: run inline, so a single-threaded runtime measures the work, not TBB.
  if (impl_->arena.max_concurrency() == 1) {
    chunk(context, 0, count);
    return;
  }
  // Inside the arena even for one chunk, so the chunk's own nested loops use its threads.
  arenaExecute(impl_->arena, [&] {
    if (count <= grain) {
      chunk(context, 0, count);
      return;
    }
    odeskin::parallelFor(tbb::blocked_range<std::size_t>(0, count, grain),
                         [&](const tbb::blocked_range<std::size_t>& r) { chunk(context, r.begin(), r.end()); });
  });
}

}  // namespace odeskin
