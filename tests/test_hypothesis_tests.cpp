// The tests behind decided comparisons (core/hypothesis_tests.hpp): values against scipy.stats,
// and the error rates of the procedures by simulation (2,000 experiments each; the bounds are the
// nominal rate plus three Monte-Carlo standard errors).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/hypothesis_tests.hpp"
#include "core/rng.hpp"

using namespace rapid;

namespace {

constexpr int kExperiments = 2000;

// Three Monte-Carlo standard errors of a rate p over kExperiments.
double mc_margin(double p) { return 3.0 * std::sqrt(p * (1.0 - p) / kExperiments); }

std::vector<double> draw(Rng& rng, int n, double mean, double sd) {
  std::vector<double> v(static_cast<std::size_t>(n));
  for (double& x : v) x = rng.normal(mean, sd);
  return v;
}

}  // namespace

// Reference values from scipy.stats 1.10 (t.cdf, ttest_ind(equal_var=False), ttest_rel).
TEST(HypothesisTests, AgreeWithScipy) {
  EXPECT_NEAR(student_t_cdf(2.0, 5), 0.9490302605850709, 1e-12);
  EXPECT_NEAR(student_t_cdf(1.0, 2.5), 0.7979694863608633, 1e-12);
  EXPECT_NEAR(student_t_cdf(-3.1, 12.7), 0.00432729099121874, 1e-12);
  EXPECT_NEAR(student_t_cdf(1.0, 1.0), 0.75, 1e-12);  // Cauchy: 1/2 + atan(1)/π
  // t.ppf (scipy 1.10), the quantiles adaptive seeds' conditional power uses.
  EXPECT_NEAR(student_t_quantile(0.975, 10), 2.2281388519649385, 1e-9);
  EXPECT_NEAR(student_t_quantile(0.99987, 58), 3.8909714316794672, 1e-9);
  EXPECT_NEAR(student_t_quantile(0.05, 3.5), -2.2224334936496013, 1e-9);
  const std::vector<double> a = {1, 2, 3, 4, 5}, b = {2, 4, 6, 8, 10};
  const MeanDifference d = welch_difference(a, b);
  EXPECT_NEAR(d.diff / d.se, -1.8973665961010275, 1e-12);
  EXPECT_NEAR(p_difference(d), 0.10753119493062718, 1e-10);
  const std::vector<double> x = {12.1, 11.4, 13.9, 12.6, 12.0, 13.1}, y = {11.0, 11.9, 10.2, 12.5, 10.8, 11.7, 11.1};
  EXPECT_NEAR(p_difference(welch_difference(x, y)), 0.027043168526771858, 1e-10);
  EXPECT_NEAR(p_difference(paired_difference(std::vector<double>{1, 3, 2, 5, 4}, std::vector<double>{0.5, 2.1, 2.2, 3.9, 3.1})),
              0.050621762549260235, 1e-10);
  EXPECT_NEAR(normal_quantile(0.975), 1.959963984540054, 1e-9);
  EXPECT_TRUE(std::isnan(p_difference(welch_difference(std::vector<double>{1}, b))));
}

TEST(HypothesisTests, HolmRejectsStepDown) {
  // Sorted: 0.005 ≤ 0.05/4, 0.01 ≤ 0.05/3, 0.03 > 0.05/2: stop.
  EXPECT_EQ(holm_rejections(std::vector<double>{0.01, 0.04, 0.03, 0.005}, 0.05),
            (std::vector<bool>{true, false, false, true}));
  EXPECT_EQ(holm_rejections(std::vector<double>{NAN, 0.001}, 0.05), (std::vector<bool>{false, true}));
  EXPECT_TRUE(holm_rejections(std::vector<double>{}, 0.05).empty());
}

// Adjusted p-values agree with the step-down rejections at every level, and with the textbook
// values (sorted 0.005, 0.01, 0.03, 0.04 → 0.02, 0.03, 0.06, 0.06).
TEST(HypothesisTests, HolmAdjustedPValuesMatchTheRejections) {
  const std::vector<double> p{0.01, 0.04, 0.03, 0.005};
  const std::vector<double> adjusted = holm_adjusted(p);
  EXPECT_NEAR(adjusted[3], 0.02, 1e-12);
  EXPECT_NEAR(adjusted[0], 0.03, 1e-12);
  EXPECT_NEAR(adjusted[2], 0.06, 1e-12);
  EXPECT_NEAR(adjusted[1], 0.06, 1e-12);
  for (const double alpha : {0.01, 0.02, 0.025, 0.03, 0.05, 0.06, 0.1}) {
    const std::vector<bool> rejected = holm_rejections(p, alpha);
    for (std::size_t i = 0; i < p.size(); ++i) EXPECT_EQ(rejected[i], adjusted[i] <= alpha) << alpha << " " << i;
  }
  const std::vector<double> with_nan = holm_adjusted(std::vector<double>{NAN, 0.4, 0.9});
  EXPECT_TRUE(std::isnan(with_nan[0]));
  EXPECT_NEAR(with_nan[1], 1.0, 1e-12);  // 0.4 · 3 capped at 1
  EXPECT_NEAR(with_nan[2], 1.0, 1e-12);
}

// No true difference: the two-sided test rejects in α of the experiments, and a Holm family of
// 12 such tests rejects anything in at most α of them.
TEST(HypothesisTests, FalseRejectionsAreAtMostAlphaBySimulation) {
  Rng rng(2024);
  int single = 0, family = 0;
  for (int e = 0; e < kExperiments; ++e) {
    std::vector<double> p;
    for (int k = 0; k < 12; ++k) {
      const auto x = draw(rng, 10, 500.0, 80.0), y = draw(rng, 10, 500.0, 120.0);  // unequal spreads
      p.push_back(p_difference(welch_difference(x, y)));
    }
    single += p[0] <= 0.05;
    const std::vector<bool> r = holm_rejections(p, 0.05);
    family += std::find(r.begin(), r.end(), true) != r.end();
  }
  EXPECT_LE(single / double(kExperiments), 0.05 + mc_margin(0.05));
  EXPECT_GE(single / double(kExperiments), 0.05 - mc_margin(0.05));  // exact for normal data
  EXPECT_LE(family / double(kExperiments), 0.05 + mc_margin(0.05));
}

// A true difference of exactly δ (the edge of equivalence): the TOST declares equivalence in at
// most α of the experiments; with no true difference and enough seeds it does so most of the time.
TEST(HypothesisTests, EquivalenceAtTheMarginIsRarelyDeclared) {
  Rng rng(7);
  const double delta = 30.0;
  int at_margin = 0, at_zero = 0;
  for (int e = 0; e < kExperiments; ++e) {
    at_margin += p_equivalence(welch_difference(draw(rng, 10, 530.0, 60.0), draw(rng, 10, 500.0, 60.0)), delta) <= 0.05;
    at_zero += p_equivalence(welch_difference(draw(rng, 40, 500.0, 40.0), draw(rng, 40, 500.0, 40.0)), delta) <= 0.05;
  }
  EXPECT_LE(at_margin / double(kExperiments), 0.05 + mc_margin(0.05));
  EXPECT_GE(at_zero / double(kExperiments), 0.9);
}

// seeds_needed's n detects a true difference of the effect with about the stated power (the
// normal approximation is slightly optimistic against the t test at small n).
TEST(HypothesisTests, SeedsNeededGiveTheStatedPowerBySimulation) {
  const double sd = 100.0, effect = 100.0;
  const int n = seeds_needed(sd, effect, 0.05, 0.8);
  EXPECT_EQ(n, 16);  // 2·(1.96 + 0.84)²
  Rng rng(11);
  int detected = 0;
  for (int e = 0; e < kExperiments; ++e)
    detected += p_difference(welch_difference(draw(rng, n, 600.0, sd), draw(rng, n, 500.0, sd))) <= 0.05;
  EXPECT_GE(detected / double(kExperiments), 0.8 - 0.03 - mc_margin(0.8));
  EXPECT_LE(detected / double(kExperiments), 0.8 + mc_margin(0.8));
}
