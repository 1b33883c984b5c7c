// A counting allocator that tells apart allocations made inside one shared library (libsumo) from
// all the others. It builds on tests/alloc_counter.cpp (link both): while counting, every
// allocation's call stack is walked, and it counts as the library's if any frame lies in the
// library's code.
//
// Why: libsumo's own allocations inside its calls (the strings and vectors its getters return, the
// simulation's per-step work) are outside the harness's allocation budget, but they are counted and
// reported; everything else in an env decision must allocate nothing.
#pragma once

#include <cstddef>

namespace rapid::test {

struct AllocationCounts {
  std::size_t total = 0;
  std::size_t in_library = 0;  // with a frame of the watched library on the call stack
  std::size_t in_function = 0; // of those, with the watched function on the call stack
  std::size_t outside_library() const { return total - in_library; }
};

// Remembers where the shared object whose path contains `library_name` has its code. Call once,
// after the library is loaded and before counting; returns false if no such object is loaded.
bool watch_library(const char* library_name);
// Also counts, among the library's allocations, those made inside one of its functions (by its
// mangled name, e.g. libsumo::Simulation::step). Returns false if the symbol is not found.
bool watch_function(const char* mangled_name);

void start_counting();
AllocationCounts stop_counting();

}  // namespace rapid::test
