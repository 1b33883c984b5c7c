#include "tests/perf/library_alloc_counter.hpp"

#include "tests/alloc_counter.hpp"

#include <atomic>
#include <cstdint>
#include <cstring>
#include <dlfcn.h>
#include <execinfo.h>
#include <link.h>

namespace {

// Executable segments of the watched library: a fixed table, so classifying needs no allocation.
struct Range {
  std::uintptr_t begin, end;
};
constexpr int kMaxRanges = 8;
Range g_ranges[kMaxRanges];
int g_range_count = 0;
Range g_function{0, 0};

std::atomic<std::size_t> g_in_library{0}, g_in_function{0};

bool in_library(const void* pc) {
  const auto a = reinterpret_cast<std::uintptr_t>(pc);
  for (int i = 0; i < g_range_count; ++i)
    if (a >= g_ranges[i].begin && a < g_ranges[i].end) return true;
  return false;
}

// The hook tests/alloc_counter.cpp calls for each counted allocation. Walking the stack may itself
// allocate (the unwinder, first time round); alloc_counter neither counts nor hooks those.
void classify() {
  void* frames[48];
  const int n = backtrace(frames, 48);
  bool library = false, function = false;
  for (int i = 0; i < n; ++i) {
    const auto pc = reinterpret_cast<std::uintptr_t>(frames[i]);
    library = library || in_library(frames[i]);
    function = function || (pc >= g_function.begin && pc < g_function.end);
  }
  if (library) g_in_library.fetch_add(1, std::memory_order_relaxed);
  if (function) g_in_function.fetch_add(1, std::memory_order_relaxed);
}

int collect_ranges(dl_phdr_info* info, std::size_t, void* name) {
  if (info->dlpi_name == nullptr || std::strstr(info->dlpi_name, static_cast<const char*>(name)) == nullptr) return 0;
  for (int i = 0; i < info->dlpi_phnum && g_range_count < kMaxRanges; ++i) {
    const ElfW(Phdr)& ph = info->dlpi_phdr[i];
    if (ph.p_type != PT_LOAD || (ph.p_flags & PF_X) == 0) continue;
    const std::uintptr_t begin = info->dlpi_addr + ph.p_vaddr;
    g_ranges[g_range_count++] = {begin, begin + ph.p_memsz};
  }
  return 1;
}

}  // namespace

namespace rapid::test {

bool watch_library(const char* library_name) {
  g_range_count = 0;
  dl_iterate_phdr(collect_ranges, const_cast<char*>(library_name));
  // The first backtrace() loads the unwinder (and allocates): do it now, outside any count.
  void* frames[4];
  backtrace(frames, 4);
  return g_range_count > 0;
}

bool watch_function(const char* mangled_name) {
  void* address = dlsym(RTLD_DEFAULT, mangled_name);
  if (address == nullptr) return false;
  Dl_info info;
  ElfW(Sym)* symbol = nullptr;
  if (dladdr1(address, &info, reinterpret_cast<void**>(&symbol), RTLD_DL_SYMENT) == 0 || symbol == nullptr)
    return false;
  const auto begin = reinterpret_cast<std::uintptr_t>(address);
  g_function = {begin, begin + symbol->st_size};
  return symbol->st_size > 0;
}

void start_counting() {
  g_in_library = 0;
  g_in_function = 0;
  set_allocation_hook(classify);
  start_counting_allocations();
}

AllocationCounts stop_counting() {
  const std::size_t total = stop_counting_allocations();
  set_allocation_hook(nullptr);
  return {total, g_in_library.load(), g_in_function.load()};
}

}  // namespace rapid::test
