#include "core/bounds.hpp"

#include <cstdio>

namespace rapid {

namespace {
std::string number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", x);
  return buf;
}
}  // namespace

bool Bounds::contains(double x) const {
  return (lo_open ? x > lo : x >= lo) && (hi_open ? x < hi : x <= hi);
}

std::string Bounds::text() const {
  const bool no_lo = lo == -std::numeric_limits<double>::infinity();
  const bool no_hi = hi == std::numeric_limits<double>::infinity();
  if (no_lo && no_hi) return "";
  if (no_hi) {
    if (lo == 0) return lo_open ? "positive" : "≥ 0";
    return (lo_open ? "above " : "at least ") + number(lo);
  }
  if (no_lo) return (hi_open ? "below " : "at most ") + number(hi);
  return std::string("in ") + (lo_open ? "(" : "[") + number(lo) + ", " + number(hi) + (hi_open ? ")" : "]");
}

}  // namespace rapid
