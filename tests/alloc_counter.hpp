// A counting allocator for tests: linking alloc_counter.cpp into a test binary replaces malloc
// and friends (glibc allows the main program to do so) with versions that count calls while
// counting is on. operator new goes through malloc, so C++ allocations are counted too.
#pragma once

#include <cstddef>

namespace rapid::test {

void start_counting_allocations();
// Stops counting and returns the number of allocations since start.
std::size_t stop_counting_allocations();

// Called after each counted allocation, e.g. to classify it by its call stack. Allocations made
// inside the hook itself are neither counted nor passed to it. nullptr removes the hook.
using AllocationHook = void (*)();
void set_allocation_hook(AllocationHook hook);

}  // namespace rapid::test
