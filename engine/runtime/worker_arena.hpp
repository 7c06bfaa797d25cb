// SPDX-License-Identifier: MIT
// A TBB arena sized once (runtime options' thread count) so per-frame parallel loops neither create
// arenas nor spill onto threads the engine did not grant. TBB stays out of this header.
#pragma once

#include <cstddef>
#include <memory>

namespace odeskin {

class WorkerArena {
 public:
  // `threads` workers including the caller; 0 = every hardware thread. A count above usableThreads
  // (engine/core/thread_count.hpp: the machine's, or what a tbb::global_control allows) is capped, and
  // threads() gives the capped count.
  explicit WorkerArena(unsigned threads = 0);
  WorkerArena(WorkerArena&&) noexcept;
  WorkerArena& operator=(WorkerArena&&) noexcept;
  ~WorkerArena();

  unsigned threads() const;

  // body(begin, end) over [0, count) in chunks of at least `grain`, on the arena's threads; returns
  // when every chunk is done. Nested TBB loops inside `body` stay in this arena. body must not throw.
  template <typename Body>
  void parallelFor(std::size_t count, std::size_t grain, const Body& body) const {
    run(count, grain, [](const void* context, std::size_t begin, std::size_t end) {
      (*static_cast<const Body*>(context))(begin, end);
    }, &body);
  }

 private:
  using Chunk = void (*)(const void* context, std::size_t begin, std::size_t end);
  void run(std::size_t count, std::size_t grain, Chunk chunk, const void* context) const;

  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace odeskin
