// Elapsed wall time on the monotonic clock, in seconds: what the trainer, the jobs, the sweep
// runner and the benchmarks time themselves with.
#pragma once

#include <chrono>

namespace rapid {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace rapid
