// Successive halving as a function of the scores: the planted best candidate wins, half (rounded
// up) goes on after each rung, ties go to the lower index (the defaults), and a rung with a
// missing score is where the search waits.
#include <gtest/gtest.h>

#include "experiments/tune/halving.hpp"

namespace rapid {
namespace {

SearchSpace space_of(int candidates, std::vector<int> rungs) {
  SearchSpace s;
  s.candidates = candidates;
  s.rungs = std::move(rungs);
  return s;
}

TEST(Halving, ThePlantedBestWinsAndHalfGoesOnEachRung) {
  const SearchSpace s = space_of(8, {1, 2, 4});
  EXPECT_EQ(rung_sizes(s), (std::vector<int>{8, 4, 2}));
  EXPECT_EQ(units_per_search(s), 8 + 4 + 2 * 2);
  std::vector<std::pair<int, int>> asked;
  // Candidate 5 is best with enough seeds; at one unit candidate 2 looks better (noise).
  const HalvingState h = replay_halving(s, [&](int k, int units) -> std::optional<double> {
    asked.emplace_back(k, units);
    if (units == 1 && k == 2) return 100.0;
    if (k == 5) return 50.0;
    return static_cast<double>(k);
  });
  ASSERT_TRUE(h.finished());
  EXPECT_EQ(h.winner, 5);
  // Rung 1: all 8 at 1 unit; rung 2: the best 4 (2, 5, 7, 6) at 2; rung 3: the best 2 (5, 7) at 4.
  EXPECT_EQ(asked.size(), 8u + 4u + 2u);
  EXPECT_EQ(asked[8], std::make_pair(2, 2));
  EXPECT_EQ(asked.back(), std::make_pair(7, 4));
}

TEST(Halving, TiesGoToTheDefaultsAndAMissingScoreWaits) {
  const SearchSpace s = space_of(4, {1, 3});
  const HalvingState tie = replay_halving(s, [](int, int) -> std::optional<double> { return 1.0; });
  EXPECT_EQ(tie.winner, 0);
  const HalvingState waiting = replay_halving(s, [](int k, int units) -> std::optional<double> {
    if (units == 3 && k == 3) return std::nullopt;
    return static_cast<double>(k);
  });
  EXPECT_FALSE(waiting.finished());
  EXPECT_EQ(waiting.rung, 1u);
  EXPECT_EQ(waiting.alive, (std::vector<int>{2, 3}));
  EXPECT_EQ(best_of({0, 1, 2, 3}, {2.0, 3.0, 3.0, 1.0}, 2), (std::vector<int>{1, 2}));
}

}  // namespace
}  // namespace rapid
