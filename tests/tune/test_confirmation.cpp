// The confirmation stage's statistics (experiments/tune/confirmation.hpp, issue #71) and the error
// rates of the whole tuning procedure by simulation, with and without it. The candidates' unit
// scores are normal around their true means, a seed effect shared on each unit (ρ = 0.3); σ = 1
// unit of seed noise; rungs 1, 2, 4 over 8 candidates (the flow campaign's). Without the stage the
// search adopts a worse setting most of the time when the defaults are best (the audit's 66 %);
// with it, at most α.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "experiments/tune/confirmation.hpp"

namespace rapid {
namespace {

SearchSpace flow_like_space() {
  SearchSpace s;
  s.candidates = 8;
  s.rungs = {1, 2, 4};
  for (std::uint64_t k = 50; k < 62; ++k) s.seeds.push_back(k);
  return s;
}

constexpr double kRho = 0.3;
constexpr double kAlpha = 0.05;
constexpr int kExperiments = 4000;

TEST(Confirmation, PowerAndUnitsAgreeWithTheNormalApproximation) {
  // z_{0.95} + z_{0.8} = 2.486: n ≈ (2.486 · sd / δ)² for large n, a little more for the t.
  const int n = confirmation_units(2.0, 1.0, kAlpha, 0.8, 1000);
  EXPECT_GE(n, 25);
  EXPECT_LE(n, 28);
  EXPECT_GE(confirmation_power(n, 2.0, 1.0, kAlpha), 0.8);
  EXPECT_LT(confirmation_power(n - 1, 2.0, 1.0, kAlpha), 0.8);
  EXPECT_EQ(confirmation_units(2.0, 1.0, kAlpha, 0.8, 10), 10);  // capped: the fresh seeds there are
}

TEST(Confirmation, TheTestIsOneSidedAndPaired) {
  const std::vector<double> defaults = {10, 20, 30, 40, 50};
  std::vector<double> better = defaults, worse = defaults;
  const double shift[] = {1.1, 0.9, 1.2, 0.8, 1.0};
  for (int i = 0; i < 5; ++i) better[i] += shift[i], worse[i] -= shift[i];
  const ConfirmationTest up = confirm_winner(better, defaults, kAlpha);
  EXPECT_TRUE(up.adopted);  // the seed effect (10 … 50) cancels in the pairs
  EXPECT_NEAR(up.mean, 1.0, 1e-12);
  EXPECT_LT(up.p, 1e-4);
  const ConfirmationTest down = confirm_winner(worse, defaults, kAlpha);
  EXPECT_FALSE(down.adopted);
  EXPECT_GT(down.p, 0.99);
}

TEST(Confirmation, TheSpreadOfPairedUnitsIsTheirDifferencesSd) {
  // Candidate 1 = candidate 0 + 5 + (±1): the differences' sd around 5 is 1 (and candidate 2 ran
  // one unit: no pair with it counts).
  const std::vector<std::vector<double>> units = {{100, 200, 300, 400}, {106, 204, 306, 404}, {7}};
  EXPECT_NEAR(paired_unit_spread(units), std::sqrt(4.0 / 3.0), 1e-12);
  EXPECT_TRUE(std::isnan(paired_unit_spread({{1}, {2}})));
}

// The tuning curve (issue #71 item 4): the expected best of k candidates drawn without replacement,
// exactly; and the gain equal candidates show by chance, E[max of k standard normals] × the noise.
TEST(TuningCurve, IsTheExactExpectedBestAndItsNoiseAlone) {
  EXPECT_DOUBLE_EQ(expected_best_of({4, 1, 3, 2}, 1), 2.5);
  EXPECT_NEAR(expected_best_of({4, 1, 3, 2}, 2), 20.0 / 6.0, 1e-12);  // the six pairs' maxima: 2, 3, 4, 3, 4, 4
  EXPECT_DOUBLE_EQ(expected_best_of({4, 1, 3, 2}, 4), 4.0);
  EXPECT_TRUE(std::isnan(expected_best_of({1, 2}, 3)));
  const std::vector<TuningCurvePoint> curve = tuning_curve({0, 0, 0, 0}, 2.0, 200, 9);
  ASSERT_EQ(curve.size(), 4u);
  EXPECT_NEAR(curve[1].noise_alone, 2.0 / std::sqrt(M_PI), 0.03);  // E[max of 2] = 1/√π
  EXPECT_NEAR(curve[3].noise_alone, 2.0 * 1.0294, 0.04);            // E[max of 4] = 1.0294
  EXPECT_EQ(curve[3].expected_best, 0.0);
  EXPECT_EQ(curve[3].lo, 0.0);
  EXPECT_EQ(curve[3].hi, 0.0);
}

// When the defaults are truly best, by half a unit of seed noise, halving alone adopts a worse
// setting most of the time; with the confirmation, at most α (whatever the units).
TEST(TuningProcedure, AdoptsAWorseSettingAtMostAlphaWithTheConfirmation) {
  const SearchSpace space = flow_like_space();
  std::vector<double> means(8, -0.5);
  means[0] = 0.0;
  const TuningOutcomes today = simulate_tuning(space, means, 1.0, kRho, false, 0, kAlpha, kExperiments, 1);
  EXPECT_GT(today.adopted_worse, 0.5) << "the procedure before issue #71";
  for (int units : {5, 20}) {
    const TuningOutcomes now = simulate_tuning(space, means, 1.0, kRho, true, units, kAlpha, kExperiments, 2);
    EXPECT_LE(now.adopted_worse, kAlpha) << units << " units";
  }
  // All equal: a non-default is adopted by chance at most α (it was the rule without the stage).
  const std::vector<double> equal(8, 0.0);
  EXPECT_GT(simulate_tuning(space, equal, 1.0, kRho, false, 0, kAlpha, kExperiments, 3).adopted_non_default, 0.8);
  EXPECT_LE(simulate_tuning(space, equal, 1.0, kRho, true, 20, kAlpha, kExperiments, 4).adopted_non_default, kAlpha + 0.01);
}

// A winner truly better by δ is adopted with probability at least 0.8 at the units sized for δ
// (every non-default candidate δ-better, so whichever wins is). The seed effect cancels in the
// pairs: the differences' sd is σ·√(2(1 − ρ)).
TEST(TuningProcedure, AdoptsADeltaBetterWinnerWithProbabilityAtLeastPower) {
  const SearchSpace space = flow_like_space();
  const double delta = 0.75, sd_pairs = std::sqrt(2.0 * (1.0 - kRho));
  const int units = confirmation_units(sd_pairs, delta, kAlpha, 0.8, 1000);
  std::vector<double> means(8, delta);
  means[0] = 0.0;
  const TuningOutcomes now = simulate_tuning(space, means, 1.0, kRho, true, units, kAlpha, kExperiments, 5);
  EXPECT_GE(now.adopted_non_default, 0.8 - 0.02) << units << " units";  // 0.02: the simulation's own error
  EXPECT_LT(now.adopted_non_default, 0.95);
}

}  // namespace
}  // namespace rapid
