// Statistics on a dataset small enough to compute by hand.
#include <gtest/gtest.h>

#include <cmath>

#include "core/dataset_stats.hpp"
#include "tests/datasets/dataset_fixtures.hpp"

namespace rapid {
namespace {

// Rewards 1 2 3 | 4 5 | 6: a terminal episode, a timeout episode, a trailing partial one.
Dataset hand_made() {
  Dataset d = testing::make_dataset(2, 1, {3, 2, 1}, 1, /*trailing_partial=*/true);
  d.rewards << 1, 2, 3, 4, 5, 6;
  return d;
}

TEST(DatasetStats, EpisodesEndAtTerminalsAndTimeoutsAndTheTailCounts) {
  const std::vector<Episode> eps = split_episodes(hand_made());
  ASSERT_EQ(eps.size(), 3u);
  EXPECT_EQ(eps[0].begin, 0u);
  EXPECT_EQ(eps[0].end, 3u);
  EXPECT_TRUE(eps[0].terminal);
  EXPECT_EQ(eps[1].begin, 3u);
  EXPECT_EQ(eps[1].end, 5u);
  EXPECT_FALSE(eps[1].terminal);
  EXPECT_EQ(eps[2].begin, 5u);
  EXPECT_EQ(eps[2].end, 6u);
  EXPECT_DOUBLE_EQ(eps[0].ret, 6.0);
  EXPECT_DOUBLE_EQ(eps[1].ret, 9.0);
  EXPECT_DOUBLE_EQ(eps[2].ret, 6.0);
}

TEST(DatasetStats, HandComputedNumbers) {
  const DatasetStats s = dataset_stats(hand_made(), 5);
  EXPECT_EQ(s.transitions, 6u);
  EXPECT_EQ(s.episodes, 3u);
  EXPECT_EQ(s.terminal_episodes, 1u);
  EXPECT_DOUBLE_EQ(s.episode_length_mean, 2.0);
  // Returns 6, 9, 6: mean 7, population variance (1 + 4 + 1) / 3 = 2.
  EXPECT_DOUBLE_EQ(s.return_mean, 7.0);
  EXPECT_DOUBLE_EQ(s.return_std, std::sqrt(2.0));
  EXPECT_DOUBLE_EQ(s.return_min, 6.0);
  EXPECT_DOUBLE_EQ(s.return_max, 9.0);
  // Rewards 1..6: mean 3.5, variance 17.5 / 6.
  EXPECT_DOUBLE_EQ(s.reward_mean, 3.5);
  EXPECT_DOUBLE_EQ(s.reward_std, std::sqrt(17.5 / 6.0));
  EXPECT_DOUBLE_EQ(s.reward_min, 1.0);
  EXPECT_DOUBLE_EQ(s.reward_max, 6.0);
  // Five bins over [1, 6]; the maximum belongs to the last, closed bin.
  EXPECT_EQ(s.reward_histogram.edges, (std::vector<double>{1, 2, 3, 4, 5, 6}));
  EXPECT_EQ(s.reward_histogram.counts, (std::vector<std::size_t>{1, 1, 1, 1, 2}));
  EXPECT_EQ(s.reward_histogram.outside, 0u);
}

TEST(DatasetStats, ImitatedSharesCountTheStepsAboveEpsilonByReturnWindow) {
  const Dataset d = hand_made();  // rewards 1 2 3 | 4 5 | 6
  const std::vector<double> eps{0.0, 2.0, 4.5, 6.0};
  // Per step: r > ε for 6, 5 (r ≥ 3), 2 (5 and 6), 0 of the six transitions.
  const std::vector<double> step = imitated_shares(d, eps, 1);
  EXPECT_EQ(step, (std::vector<double>{1.0, 4.0 / 6, 2.0 / 6, 0.0}));
  // Window 2, cut at each episode's end: means 1.5 2.5 3 | 4.5 5 | 6.
  const std::vector<double> window = imitated_shares(d, eps, 2);
  EXPECT_EQ(window, (std::vector<double>{1.0, 5.0 / 6, 2.0 / 6, 0.0}));
  EXPECT_THROW(imitated_shares(d, eps, 0), std::invalid_argument);
}

TEST(DatasetStats, SharedEdgesCountWhatFallsOutside) {
  const DatasetStats s = dataset_stats_with_edges(hand_made(), {0.0, 2.5, 5.0});
  EXPECT_EQ(s.reward_histogram.counts, (std::vector<std::size_t>{2, 3}));  // {1, 2} and {3, 4, 5}
  EXPECT_EQ(s.reward_histogram.outside, 1u);                                // 6
}

TEST(DatasetStats, DefaultHistogramHasFortyBinsHoldingEveryTransition) {
  const Dataset d = testing::make_dataset(3, 2, {50, 70, 30});
  const DatasetStats s = dataset_stats(d);
  ASSERT_EQ(s.reward_histogram.counts.size(), static_cast<std::size_t>(kDefaultHistogramBins));
  std::size_t total = 0;
  for (std::size_t c : s.reward_histogram.counts) total += c;
  EXPECT_EQ(total, d.size());
  EXPECT_EQ(s.reward_histogram.edges.front(), s.reward_min);
  EXPECT_EQ(s.reward_histogram.edges.back(), s.reward_max);
}

TEST(DatasetStats, ConstantRewardsGetAUnitWideRange) {
  Dataset d = hand_made();
  d.rewards.setConstant(2.0f);
  const DatasetStats s = dataset_stats(d, 2);
  EXPECT_EQ(s.reward_histogram.edges, (std::vector<double>{1.5, 2.0, 2.5}));
  EXPECT_EQ(s.reward_histogram.counts, (std::vector<std::size_t>{0, 6}));
  EXPECT_DOUBLE_EQ(s.reward_std, 0.0);
}

// A valid dataset whose rewards are all huge and equal (1e38): ±0.5 is below rounding there, so
// the range widens relative to the value; a degenerate histogram is still a histogram.
TEST(DatasetStats, HugeEqualRewardsStillHaveAHistogram) {
  Dataset d = hand_made();
  d.rewards.setConstant(1e38f);
  const DatasetStats s = dataset_stats(d, 10);
  ASSERT_EQ(s.reward_histogram.counts.size(), 10u);
  std::size_t in = 0;
  for (std::size_t c : s.reward_histogram.counts) in += c;
  EXPECT_EQ(in, 6u);
  EXPECT_EQ(s.reward_histogram.outside, 0u);
  // Ends a few ulps apart: one bin, everything in it.
  const std::vector<double> narrow = uniform_edges(1e38, std::nextafter(1e38, 2e38), 10);
  EXPECT_EQ(narrow.size(), 2u);
  EXPECT_LT(narrow[0], narrow[1]);
}

TEST(DatasetStats, BadHistogramArgumentsThrow) {
  EXPECT_THROW(uniform_edges(0.0, 1.0, 0), std::invalid_argument);
  EXPECT_THROW(uniform_edges(1.0, 0.0, 4), std::invalid_argument);
  EXPECT_THROW(make_histogram({}, {1.0}), std::invalid_argument);
  EXPECT_THROW(make_histogram({}, {0.0, 1.0, 1.0}), std::invalid_argument);
}

}  // namespace
}  // namespace rapid
