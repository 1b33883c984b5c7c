// The confirmation stage of `rapid tune` (docs/tuning.md §Confirmation, issue #71). Successive
// halving picks its winner by a few units of seed noise: if all candidates were equal, a
// non-default one would win almost every time. So a winner that is not the defaults replaces them
// only when it beats them again on fresh tuning seeds, paired by seed (the same seed gives both the
// same dataset draw and traffic), by a one-sided paired t test at level α. The units of that test
// are sized from the search's own spread so that a winner truly better by δ (the scenario's decision
// margin) is adopted with probability `power`; the error rates of the whole procedure are measured
// by simulation (simulate_tuning, tests/tune/test_confirmation.cpp).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "experiments/tune/space.hpp"

namespace rapid {

// unit_scores[k][u]: candidate k's score on its unit u alone (the mean over the datasets of that
// unit's final returns); a candidate has as many as it ran. The standard deviation of the
// difference of two candidates' scores on the same unit, around their mean difference: pooled over
// every pair of candidates with at least two units in common (the later rungs). NaN when no pair has.
double paired_unit_spread(const std::vector<std::vector<double>>& unit_scores);

// Power of the one-sided paired t test at level `alpha` with `units` pairs, when the true mean
// difference is `delta` and the pairs' standard deviation `sd` (the shifted-t approximation of the
// noncentral t: P(T_{n−1} > t_{1−α} − δ√n/sd)).
double confirmation_power(int units, double sd, double delta, double alpha);

// The fewest units (from 3) whose power reaches `power`; `max_units` when none up to it does.
int confirmation_units(double sd, double delta, double alpha, double power, int max_units);

struct ConfirmationTest {
  int units = 0;
  double mean = 0.0;   // winner − defaults, per unit
  double se = 0.0;
  double p = 1.0;      // one-sided: H0 the winner is no better than the defaults
  bool adopted = false;
};
// The test on the units' paired scores (same size, ≥ 2): adopted when p < alpha.
ConfirmationTest confirm_winner(std::span<const double> winner, std::span<const double> defaults, double alpha);

// What the procedure does to candidates with true mean scores `means` (0: the defaults), when a
// unit's score is the candidate's mean plus a seed effect the candidates share on that unit
// (correlation `rho`) plus noise, of total standard deviation `sd` per unit: successive halving
// over `space.rungs` (replay_halving, the procedure `rapid tune` runs), then, when `confirm`, the
// confirmation at `alpha` with `confirm_units` units on fresh seeds.
struct TuningOutcomes {
  double adopted_non_default = 0;  // a candidate other than the defaults replaced them
  double adopted_worse = 0;        // the adopted candidate's true mean is below the defaults'
  double adopted_best = 0;         // the adopted candidate is the truly best one (not the defaults)
  double runs_per_search = 0;      // units run, search and confirmation, per experiment
};
TuningOutcomes simulate_tuning(const SearchSpace& space, const std::vector<double>& means, double sd, double rho,
                               bool confirm, int confirm_units, double alpha, int experiments, std::uint64_t seed);

// A tuning curve (issue #71, "honest sensitivity"): the expected best of k candidates drawn at
// random without replacement from `scores` (each one unit's score of a candidate), exactly, over
// every such draw; −∞ (a diverged candidate) is the lowest score. With a 95 % interval from
// resampling the candidates (percentile bootstrap, `replicates`, seeded), and what noise alone
// would give: `unit_noise` × the expected best of k standard normals, the gain k equal candidates
// show by chance.
struct TuningCurvePoint {
  int k = 0;
  double expected_best = 0.0, lo = 0.0, hi = 0.0;
  double noise_alone = 0.0;  // expected best of k equal candidates above their mean
};
double expected_best_of(std::vector<double> scores, int k);
std::vector<TuningCurvePoint> tuning_curve(const std::vector<double>& scores, double unit_noise, int replicates,
                                           std::uint64_t seed);

}  // namespace rapid
