// core/statistics: hand-checked values, and a bootstrap that is the same whatever the thread count.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <vector>

#include "core/statistics.hpp"

namespace rapid {
namespace {

TEST(Statistics, MeanAndPopulationStd) {
  const std::vector<double> x = {1, 2, 3, 4};
  EXPECT_DOUBLE_EQ(mean(x), 2.5);
  EXPECT_DOUBLE_EQ(population_std(x), std::sqrt(1.25));
  EXPECT_DOUBLE_EQ(population_std(std::vector<double>{7}), 0.0);
  EXPECT_TRUE(std::isnan(mean(std::vector<double>{})));
}

TEST(Statistics, IqmOfEightValuesIsTheMeanOfTheMiddleFour) {
  // Sorted: -50 1 | 3 5 6 7 | 10 100.
  const std::vector<double> x = {10, 1, 7, 3, 100, 5, -50, 6};
  EXPECT_DOUBLE_EQ(iqm(x), (3 + 5 + 6 + 7) / 4.0);
}

TEST(Statistics, IqmTrimsFloorOfAQuarterFromEachEnd) {
  EXPECT_DOUBLE_EQ(iqm(std::vector<double>{1, 2, 30}), 11.0);  // 3 / 4 = 0: nothing trimmed
  // 10 values: 2 trimmed at each end, the middle 6 averaged.
  EXPECT_DOUBLE_EQ(iqm(std::vector<double>{0, 1, 2, 3, 4, 5, 6, 7, 8, 9}), 4.5);
  EXPECT_DOUBLE_EQ(iqm(std::vector<double>{-1000, 1, 2, 3, 4, 5, 6, 7, 8, 1000}), 4.5);
}

TEST(Statistics, QuantileInterpolatesLinearly) {
  EXPECT_DOUBLE_EQ(quantile({4, 1, 3, 2}, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(quantile({4, 1, 3, 2}, 1.0), 4.0);
  EXPECT_DOUBLE_EQ(quantile({4, 1, 3, 2}, 0.5), 2.5);
  EXPECT_DOUBLE_EQ(quantile({0, 10}, 0.025), 0.25);
}

TEST(Statistics, ProbabilityOfImprovementCountsTiesHalf) {
  EXPECT_DOUBLE_EQ(probability_of_improvement(std::vector<double>{3, 4}, std::vector<double>{1, 2}), 1.0);
  EXPECT_DOUBLE_EQ(probability_of_improvement(std::vector<double>{1, 2}, std::vector<double>{3, 4}), 0.0);
  // Pairs (1,2) (1,3) (2,2) (2,3): one tie → 0.5 / 4.
  EXPECT_DOUBLE_EQ(probability_of_improvement(std::vector<double>{1, 2}, std::vector<double>{2, 3}), 0.125);
  const std::vector<double> same = {5, 1, 3};
  EXPECT_DOUBLE_EQ(probability_of_improvement(same, same), 0.5);
  EXPECT_TRUE(std::isnan(probability_of_improvement(std::vector<double>{}, same)));
}

TEST(Statistics, BootstrapIntervalIsTheSameWithOneOrTwoThreads) {
  const Strata strata = {{1, 5, 2, 8, 3, 9, 4, 7}, {10, 12, 11}, {-3, 0}};
  const BootstrapOptions options{5000, 42, 0.95, 0};  // min_parallel_work 0: always use the thread team
  omp_set_num_threads(1);
  const Interval one = stratified_bootstrap_ci(strata, pooled_iqm, options);
  omp_set_num_threads(2);
  const Interval two = stratified_bootstrap_ci(strata, pooled_iqm, options);
  EXPECT_EQ(one.lo, two.lo);  // bit-identical, not merely close
  EXPECT_EQ(one.hi, two.hi);
  EXPECT_LT(one.lo, one.hi);
  EXPECT_TRUE(one.contains(pooled_iqm(strata)));
  // The same call again gives the same bits; another seed draws other replicates (the mean takes
  // many distinct values, so the interval's ends move).
  const Interval again = stratified_bootstrap_ci(strata, pooled_iqm, options);
  EXPECT_EQ(one.lo, again.lo);
  const Interval mean_a = stratified_bootstrap_ci(strata, pooled_mean, BootstrapOptions{5000, 42, 0.95, 0});
  const Interval mean_b = stratified_bootstrap_ci(strata, pooled_mean, BootstrapOptions{5000, 43, 0.95, 0});
  EXPECT_TRUE(mean_a.lo != mean_b.lo || mean_a.hi != mean_b.hi);
}

TEST(Statistics, BootstrapKeepsStrataApart) {
  // Resampling within strata keeps one value of each: the pooled mean can never move.
  const Strata strata = {{1}, {3}};
  const Interval ci = stratified_bootstrap_ci(strata, pooled_mean, BootstrapOptions{1000, 1, 0.95, 0});
  EXPECT_DOUBLE_EQ(ci.lo, 2.0);
  EXPECT_DOUBLE_EQ(ci.hi, 2.0);
}

TEST(Statistics, BootstrapIntervalOfTheMeanStaysWithinTheData) {
  const Strata strata = {{2, 4, 6, 8, 10}};
  const Interval ci = stratified_bootstrap_ci(strata, pooled_mean, BootstrapOptions{4000, 7, 0.95, 0});
  EXPECT_GE(ci.lo, 2.0);
  EXPECT_LE(ci.hi, 10.0);
  EXPECT_TRUE(ci.contains(6.0));
  EXPECT_THROW(stratified_bootstrap_ci(Strata{{}}, pooled_mean, {}), std::invalid_argument);
}

}  // namespace
}  // namespace rapid
