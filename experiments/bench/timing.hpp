// Small timing helpers shared by the `rapid bench` measurements. The machines are shared and
// noisy, so every reported number is a median over repeats, and compared quantities are measured
// interleaved in the same run (see env_speed.cpp, update_speed.cpp).
#pragma once

#include <algorithm>
#include <vector>

#include "core/clock.hpp"

namespace rapid::bench {

// Median of `v` (0 for an empty vector); takes a copy because it reorders.
inline double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const std::size_t mid = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(mid), v.end());
  const double upper = v[mid];
  if (v.size() % 2 == 1) return upper;
  return 0.5 * (upper + *std::max_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(mid)));
}

}  // namespace rapid::bench
