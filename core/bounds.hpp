// An interval of numbers whose ends may be open, closed or absent: the values a setting accepts.
// The config-key table (experiments/run/config_keys.hpp) gives one per key; envs/ declares its
// scenario settings' ranges with it, so the table and the settings' own check share one range.
#pragma once

#include <limits>
#include <string>

namespace rapid {

struct Bounds {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false, hi_open = false;

  bool contains(double x) const;
  // "positive", "≥ 0", "at least 2", "in [0, 1)"; empty when every number is accepted.
  std::string text() const;
};

inline constexpr Bounds kAnyNumber{};
inline constexpr Bounds kPositive{.lo = 0, .lo_open = true};
inline constexpr Bounds kNonNegative{.lo = 0};

}  // namespace rapid
