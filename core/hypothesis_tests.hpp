// Decisions between two algorithms from their per-seed results (docs/decisions.md): Welch's
// two-sample t test for a difference, the two one-sided tests (TOST) for equivalence within a
// margin δ, their paired forms for two measurements of the same runs, Holm's step-down procedure
// for a family of such tests, and the sample size a test needs to resolve an effect.
//
// Welch's test does not assume equal variances; its t reference distribution is exact for normal
// data and close for the sums of many rewards that final returns are. The simulation tests
// (tests/test_hypothesis_tests.cpp) measure the error rates the procedures actually have.
#pragma once

#include <span>
#include <vector>

namespace rapid {

// P(T ≤ t) for Student's t with `df` > 0 degrees of freedom (df may be fractional).
double student_t_cdf(double t, double df);
// The t with P(T ≤ t) = p (0 < p < 1), by bisection on student_t_cdf.
double student_t_quantile(double p, double df);
// P(Z ≤ z) and its inverse for the standard normal.
double normal_cdf(double z);
double normal_quantile(double p);

// x − y by Welch: the difference of means, its standard error and the Welch–Satterthwaite
// degrees of freedom. Needs at least two values on each side (else every field is NaN).
struct MeanDifference {
  double diff = 0.0, se = 0.0, df = 0.0;
};
MeanDifference welch_difference(std::span<const double> x, std::span<const double> y);
// The same for paired measurements (x_i and y_i of the same run): the mean of x_i − y_i, its
// standard error and n − 1 degrees of freedom. x and y must have the same size (≥ 2).
MeanDifference paired_difference(std::span<const double> x, std::span<const double> y);

// Two-sided p-value of H0: the true difference is 0.
double p_difference(const MeanDifference& d);
// p-value of the TOST for H0: |true difference| ≥ delta (the larger of the two one-sided
// p-values); small means "equivalent within ±delta".
double p_equivalence(const MeanDifference& d, double delta);

// Holm's step-down procedure: which of the hypotheses with these p-values are rejected while the
// family-wise error rate stays at most `alpha`, for any dependence between the tests. NaN
// p-values are never rejected (and still count in the family).
std::vector<bool> holm_rejections(std::span<const double> p_values, double alpha);

// Holm's adjusted p-values: the smallest family-wise level at which each hypothesis is rejected
// (p_(k) · (m − k + 1), made non-decreasing in the sorted order, at most 1); rejected at α exactly
// when holm_rejections says so. NaN stays NaN.
std::vector<double> holm_adjusted(std::span<const double> p_values);

// Seeds per algorithm with which a two-sided test at level `alpha` detects a true difference of
// `effect` with probability `power`, at standard deviation `sd` on each side (the normal
// approximation n = 2·(z_{1−α/2} + z_power)²·sd²/effect², rounded up, at least 2).
int seeds_needed(double sd, double effect, double alpha, double power);

}  // namespace rapid
