// contains(range, x): whether x is an element of range, C++23's std::ranges::contains for the
// C++20 this project builds with (the names of a grid's scenarios, algorithms and datasets).
#pragma once

#include <algorithm>

namespace rapid {

template <class Range, class T>
bool contains(const Range& range, const T& x) {
  return std::ranges::find(range, x) != std::ranges::end(range);
}

}  // namespace rapid
