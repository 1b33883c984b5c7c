#include "tests/alloc_counter.hpp"

#include <atomic>
#include <cstdlib>

extern "C" {
void* __libc_malloc(std::size_t);
void* __libc_calloc(std::size_t, std::size_t);
void* __libc_realloc(void*, std::size_t);
void* __libc_memalign(std::size_t, std::size_t);
void __libc_free(void*);
}

namespace {
std::atomic<bool> counting{false};
std::atomic<std::size_t> count{0};
std::atomic<rapid::test::AllocationHook> hook{nullptr};
thread_local bool in_hook = false;

inline void note() {
  if (!counting.load(std::memory_order_relaxed) || in_hook) return;
  count.fetch_add(1, std::memory_order_relaxed);
  if (const auto h = hook.load(std::memory_order_relaxed)) {
    in_hook = true;
    h();
    in_hook = false;
  }
}
}  // namespace

extern "C" {
void* malloc(std::size_t n) {
  note();
  return __libc_malloc(n);
}
void* calloc(std::size_t n, std::size_t m) {
  note();
  return __libc_calloc(n, m);
}
void* realloc(void* p, std::size_t n) {
  note();
  return __libc_realloc(p, n);
}
void* memalign(std::size_t a, std::size_t n) {
  note();
  return __libc_memalign(a, n);
}
void* aligned_alloc(std::size_t a, std::size_t n) {
  note();
  return __libc_memalign(a, n);
}
int posix_memalign(void** out, std::size_t a, std::size_t n) {
  note();
  *out = __libc_memalign(a, n);
  return *out ? 0 : 12;
}
void free(void* p) { __libc_free(p); }
}

namespace rapid::test {
void start_counting_allocations() {
  count = 0;
  counting = true;
}
std::size_t stop_counting_allocations() {
  counting = false;
  return count.load();
}
void set_allocation_hook(AllocationHook h) { hook = h; }
}  // namespace rapid::test
