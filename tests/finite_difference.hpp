// Central finite differences for gradient tests.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>

namespace rapid::test {

inline bool gradients_agree(double analytic, double numeric) {
  return std::abs(analytic - numeric) <= 2e-3 + 2e-2 * std::max(std::abs(analytic), std::abs(numeric));
}

// Compares `analytic` with the central difference of `loss` in the coordinate *v. A step can
// carry a ReLU input across its kink and bend the difference; that error shrinks with the step
// while a wrong gradient does not, so a mismatch is retried with smaller steps before it counts.
// Leaves *v unchanged; the last numeric estimate goes to *numeric.
inline bool central_difference_agrees(const std::function<double()>& loss, float* v, double analytic,
                                      double* numeric) {
  const float saved = *v;
  for (float h : {1e-3f, 3e-4f, 1e-4f}) {
    *v = saved + h;
    const double up = loss();
    *v = saved - h;
    const double down = loss();
    *v = saved;
    *numeric = (up - down) / (2.0 * h);
    if (gradients_agree(analytic, *numeric)) return true;
  }
  return false;
}

}  // namespace rapid::test
