// SPDX-License-Identifier: MIT
// Replacements of the global operator new and delete that count calls and bytes, then defer to
// malloc / aligned_alloc and free (so AddressSanitizer still sees every allocation).
#include "allocation_counter.hpp"

#include <atomic>
#include <cstdlib>
#include <new>

namespace {

std::atomic<std::uint64_t> g_calls{0};
std::atomic<std::uint64_t> g_bytes{0};

void* counted(std::size_t size, std::size_t alignment) {
  g_calls.fetch_add(1, std::memory_order_relaxed);
  g_bytes.fetch_add(size, std::memory_order_relaxed);
  if (size == 0) size = 1;
  if (alignment <= alignof(std::max_align_t)) return std::malloc(size);
  // aligned_alloc wants a size that is a multiple of the alignment.
  // cppcheck-suppress zerodiv ; alignment > alignof(std::max_align_t) here, the line above returned otherwise
  return std::aligned_alloc(alignment, (size + alignment - 1) / alignment * alignment);
}

void* countedOrThrow(std::size_t size, std::size_t alignment) {
  void* p = counted(size, alignment);
  if (p == nullptr) throw std::bad_alloc();
  return p;
}

}  // namespace

namespace odeskin::testing {

AllocationCount allocationsSoFar() {
  return {g_calls.load(std::memory_order_relaxed), g_bytes.load(std::memory_order_relaxed)};
}

}  // namespace odeskin::testing

void* operator new(std::size_t size) { return countedOrThrow(size, 0); }
void* operator new[](std::size_t size) { return countedOrThrow(size, 0); }
void* operator new(std::size_t size, std::align_val_t a) { return countedOrThrow(size, static_cast<std::size_t>(a)); }
void* operator new[](std::size_t size, std::align_val_t a) { return countedOrThrow(size, static_cast<std::size_t>(a)); }
void* operator new(std::size_t size, const std::nothrow_t&) noexcept { return counted(size, 0); }
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept { return counted(size, 0); }
void* operator new(std::size_t size, std::align_val_t a, const std::nothrow_t&) noexcept {
  return counted(size, static_cast<std::size_t>(a));
}
void* operator new[](std::size_t size, std::align_val_t a, const std::nothrow_t&) noexcept {
  return counted(size, static_cast<std::size_t>(a));
}

void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t, const std::nothrow_t&) noexcept { std::free(p); }

#if defined(__SANITIZE_ADDRESS__)
// The soaks measure resident memory. AddressSanitizer keeps freed blocks in a quarantine (256 MB by
// default) before reusing them, so a driver that mallocs and frees per frame (lavapipe does, per
// submit) grows the resident size by gigabytes under ASan while the plain build stays flat. Reuse at
// once in these two programs, which are about growth, not about use-after-free; ASAN_OPTIONS from the
// environment still override this for any flag it names.
extern "C" const char* __asan_default_options() { return "quarantine_size_mb=0:thread_local_quarantine_size_kb=0"; }
#endif
