// SPDX-License-Identifier: MIT
// The TBB calls the engine makes (parallel_for, parallel_reduce, parallel_invoke,
// task_arena::execute), through wrappers that ThreadSanitizer can follow.
//
// Debian's libtbb is not built with -fsanitize=thread: TBB hands a task to a worker and joins it
// through atomics and futex waits inside libtbb.so, which TSan does not see, so TBB's own task
// objects and every write a parallel body makes and the caller reads after the join look like
// races. Under TSan these wrappers (docs/reliability.md, "ThreadSanitizer"):
//   fork: release a per-call "fork" token before the TBB call; every chunk (task) acquires it
//         before the user's code runs;
//   join: every chunk releases a separate per-call "join" token after the user's code; the caller
//         acquires it after the TBB call returns;
//   turn TSan's access checks off while a thread runs TBB's own code (from the TBB call to the
//         chunks, and between chunks on a worker) and back on for the user's code in every chunk;
// and execute_and_wait below orders the caller after TBB's last accesses to its stack.
// The tokens differ, so no chunk synchronises with another through them, and the user's code is
// always checked: a race between two chunks of one loop is still reported. Without TSan each
// wrapper is exactly the TBB call.
#pragma once

#include <cstddef>
#include <type_traits>

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_reduce.h>
#include <tbb/task_arena.h>

#if defined(__SANITIZE_THREAD__)
#define ODESKIN_TSAN 1
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define ODESKIN_TSAN 1
#endif
#endif
#ifndef ODESKIN_TSAN
#define ODESKIN_TSAN 0
#endif

#if ODESKIN_TSAN
#include <dlfcn.h>

#include <cstdint>

extern "C" {
// From <sanitizer/tsan_interface.h>, declared here so the header needs no sanitizer include path.
void __tsan_acquire(void* addr);  // NOLINT(bugprone-reserved-identifier)
void __tsan_release(void* addr);  // NOLINT(bugprone-reserved-identifier)
// TSan's dynamic annotations: the calling thread's reads / writes are not recorded or checked.
void AnnotateIgnoreReadsBegin(const char* file, int line);
void AnnotateIgnoreReadsEnd(const char* file, int line);
void AnnotateIgnoreWritesBegin(const char* file, int line);
void AnnotateIgnoreWritesEnd(const char* file, int line);
}
#endif

#if ODESKIN_TSAN
// TBB's own join, for TSan. Every TBB algorithm ends with the caller in libtbb's
// r1::execute_and_wait, which returns once the root wait_context's count is 0; the workers' last
// accesses to that context (and to the rest of the algorithm's state on the caller's stack) come
// after their chunks' join release, in TBB's fold_tree. TSan does not see libtbb read the count, so
// when the caller's stack is later reused, those accesses look like races with odeskin's code. This
// definition in the program takes the place of libtbb's for the calls TBB's headers make, calls the
// real one, and then acquires the context's own synchronisation: the workers' decrements of the
// count are instrumented atomic read-modify-writes (release) on it, so the caller is ordered after
// every worker's last access, as it really is. Weak, so every translation unit may carry it.
namespace tbb::detail::r1 {
__attribute__((weak)) void execute_and_wait(d1::task& t, d1::task_group_context& t_ctx, d1::wait_context& wait_ctx,
                                            d1::task_group_context& w_ctx) {
  using Real = void (*)(d1::task&, d1::task_group_context&, d1::wait_context&, d1::task_group_context&);
  static const auto real = reinterpret_cast<Real>(
      dlsym(RTLD_NEXT, "_ZN3tbb6detail2r116execute_and_waitERNS0_2d14taskERNS2_18task_group_contextERNS2_12wait_contextES6_"));
  real(t, t_ctx, wait_ctx, w_ctx);
  // The count's offset in wait_context is TBB's private matter: acquire at every word of it.
  auto* bytes = reinterpret_cast<char*>(&wait_ctx);
  for (std::size_t offset = 0; offset < sizeof(d1::wait_context); offset += sizeof(std::uint64_t)) {
    __tsan_acquire(bytes + offset);
  }
}
}  // namespace tbb::detail::r1
#endif

namespace odeskin {

#if ODESKIN_TSAN
namespace parallel_detail {

// Functions that run on TBB's workers before their fork acquire read memory (their own fields, the
// tokens' address, the range and values TBB passes by reference, in TBB's task memory) that TBB's
// hand-over orders but TSan cannot see, so they are not instrumented. They call the user's code
// through `call` below, which is instrumented and never inlined into them (GCC does not inline
// across different no_sanitize attributes either), so every access the user's code makes is checked.
#define ODESKIN_TSAN_UNCHECKED __attribute__((no_sanitize("thread")))

// Whether this thread's memory accesses are ignored by TSan because it is in TBB's own code: from a
// wrapper's TBB call to the first chunk it runs itself, and on a worker between chunks. TSan reports
// a thread that ends with ignores on, and TBB's workers end in TBB: the destructor ends them.
struct TbbIgnore {
  bool on = false;
  TbbIgnore() = default;
  TbbIgnore(const TbbIgnore&) = delete;
  TbbIgnore& operator=(const TbbIgnore&) = delete;
  ODESKIN_TSAN_UNCHECKED void begin() {
    if (on) return;
    AnnotateIgnoreReadsBegin(__FILE__, __LINE__);
    AnnotateIgnoreWritesBegin(__FILE__, __LINE__);
    on = true;
  }
  ODESKIN_TSAN_UNCHECKED void end() {
    if (!on) return;
    AnnotateIgnoreWritesEnd(__FILE__, __LINE__);
    AnnotateIgnoreReadsEnd(__FILE__, __LINE__);
    on = false;
  }
  ODESKIN_TSAN_UNCHECKED ~TbbIgnore() { end(); }
};
inline thread_local TbbIgnore tbb_ignore;

ODESKIN_TSAN_UNCHECKED inline void enterTbb() { tbb_ignore.begin(); }
ODESKIN_TSAN_UNCHECKED inline void leaveTbb() { tbb_ignore.end(); }

// One parallel call. The caller releases "fork" and enters TBB (ignored); each chunk leaves TBB,
// acquires fork, runs the user's code (checked), releases "join" and enters TBB again; the caller
// leaves TBB and acquires join. The tokens live on the heap so that their addresses are fresh for
// every call: TSan keys its synchronisation objects by address and drops them when the memory is
// freed (not when a stack frame is left, where a later call's token would inherit an earlier one's).
class ForkJoin {
 public:
  ODESKIN_TSAN_UNCHECKED ForkJoin() : tokens_(new Tokens) {
    __tsan_release(&tokens_->fork);
    enterTbb();
  }
  ForkJoin(const ForkJoin&) = delete;
  ForkJoin& operator=(const ForkJoin&) = delete;
  ODESKIN_TSAN_UNCHECKED ~ForkJoin() {
    leaveTbb();  // when TBB's call threw, join() did not run
    delete tokens_;
  }
  ODESKIN_TSAN_UNCHECKED void enter() const {
    leaveTbb();
    __tsan_acquire(&tokens_->fork);
  }
  ODESKIN_TSAN_UNCHECKED void leave() const {
    __tsan_release(&tokens_->join);
    enterTbb();
  }
  ODESKIN_TSAN_UNCHECKED void join() const {
    leaveTbb();
    __tsan_acquire(&tokens_->join);
  }

 private:
  struct Tokens {
    alignas(8) char fork = 0;
    alignas(8) char join = 0;
  };
  Tokens* tokens_;
};

template <typename F, typename... Args>
[[gnu::noinline]] decltype(auto) call(const F& f, const Args&... args) {
  return f(args...);
}

template <typename Body>
struct RangeChunk {
  const Body* body;
  const ForkJoin* fork_join;
  template <typename Range>
  ODESKIN_TSAN_UNCHECKED void operator()(const Range& r) const {
    static_assert(std::is_trivially_copyable_v<Range>, "parallelFor under TSan copies the range unchecked");
    const Range local = r;
    fork_join->enter();
    call(*body, local);
    fork_join->leave();
  }
};

template <typename Body>
struct IndexChunk {
  const Body* body;
  const ForkJoin* fork_join;
  template <typename Index>
  ODESKIN_TSAN_UNCHECKED void operator()(Index i) const {
    fork_join->enter();
    call(*body, i);
    fork_join->leave();
  }
};

template <typename Value, typename Body>
struct ReduceChunk {
  const Body* body;
  const ForkJoin* fork_join;
  template <typename Range>
  ODESKIN_TSAN_UNCHECKED Value operator()(const Range& r, const Value& v) const {
    static_assert(std::is_trivially_copyable_v<Range> && std::is_trivially_copyable_v<Value>,
                  "parallelReduce under TSan copies the range and the value unchecked");
    const Range local_r = r;
    const Value local_v = v;
    fork_join->enter();
    Value result = call(*body, local_r, local_v);
    fork_join->leave();
    return result;
  }
};

template <typename Value, typename Reduction>
struct ReduceJoin {
  const Reduction* reduction;
  const ForkJoin* fork_join;
  ODESKIN_TSAN_UNCHECKED Value operator()(const Value& x, const Value& y) const {
    const Value local_x = x;
    const Value local_y = y;
    fork_join->enter();
    Value result = call(*reduction, local_x, local_y);
    fork_join->leave();
    return result;
  }
};

template <typename F>
struct Task {
  const F* f;
  const ForkJoin* fork_join;
  ODESKIN_TSAN_UNCHECKED void operator()() const {
    fork_join->enter();
    call(*f);
    fork_join->leave();
  }
};

#undef ODESKIN_TSAN_UNCHECKED

}  // namespace parallel_detail
#endif

// tbb::parallel_for(range, body): body(const Range&) per chunk.
template <typename Range, typename Body>
inline void parallelFor(const Range& range, const Body& body) {
#if ODESKIN_TSAN
  const parallel_detail::ForkJoin fork_join;
  tbb::parallel_for(range, parallel_detail::RangeChunk<Body>{&body, &fork_join});
  fork_join.join();
#else
  tbb::parallel_for(range, body);
#endif
}

// tbb::parallel_for(first, last, f): f(i) for every i in [first, last).
template <typename Index, typename Function>
inline void parallelFor(Index first, Index last, const Function& f) {
#if ODESKIN_TSAN
  const parallel_detail::ForkJoin fork_join;
  tbb::parallel_for(first, last, parallel_detail::IndexChunk<Function>{&f, &fork_join});
  fork_join.join();
#else
  tbb::parallel_for(first, last, f);
#endif
}

// tbb::parallel_reduce(range, identity, body, reduction), the functional form: body(range, value)
// returns the chunk's value, reduction(x, y) combines two. Under TSan both the range and the value
// type must be trivially copyable (the wrapper copies them before it may check accesses).
template <typename Range, typename Value, typename Body, typename Reduction>
inline Value parallelReduce(const Range& range, const Value& identity, const Body& body, const Reduction& reduction) {
#if ODESKIN_TSAN
  const parallel_detail::ForkJoin fork_join;
  Value result = tbb::parallel_reduce(range, identity, parallel_detail::ReduceChunk<Value, Body>{&body, &fork_join},
                                      parallel_detail::ReduceJoin<Value, Reduction>{&reduction, &fork_join});
  fork_join.join();
  return result;
#else
  return tbb::parallel_reduce(range, identity, body, reduction);
#endif
}

// tbb::parallel_invoke(f, g, ...): runs every function, possibly at the same time.
template <typename... Functions>
inline void parallelInvoke(const Functions&... fs) {
#if ODESKIN_TSAN
  const parallel_detail::ForkJoin fork_join;
  tbb::parallel_invoke(parallel_detail::Task<Functions>{&fs, &fork_join}...);
  fork_join.join();
#else
  tbb::parallel_invoke(fs...);
#endif
}

// arena.execute(f): f runs in the arena, on the calling thread or, when the arena has no free
// slot, on one of its workers while the caller waits.
template <typename Function>
inline void arenaExecute(tbb::task_arena& arena, const Function& f) {
#if ODESKIN_TSAN
  const parallel_detail::ForkJoin fork_join;
  arena.execute(parallel_detail::Task<Function>{&f, &fork_join});
  fork_join.join();
#else
  arena.execute(f);
#endif
}

}  // namespace odeskin
