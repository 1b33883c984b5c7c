// final+medium: half of each source in whole episodes, deterministic.
#include <gtest/gtest.h>

#include "core/dataset_mix.hpp"
#include "core/dataset_stats.hpp"
#include "tests/datasets/dataset_fixtures.hpp"

namespace rapid {
namespace {

using testing::bit_identical;
using testing::make_dataset;

// Transitions [begin, end) of `d` without its metadata, to compare data only.
Dataset part(const Dataset& d, std::size_t begin, std::size_t end) {
  Dataset out = slice(d, begin, end);
  out.metadata.clear();
  return out;
}

TEST(DatasetMix, FinalPlusMediumIsHalfOfEach) {
  const Dataset final_data = make_dataset(4, 2, std::vector<int>(10, 10), 1);  // 100 transitions
  const Dataset medium_data = make_dataset(4, 2, std::vector<int>(20, 5), 2);  // 100 transitions
  const Dataset mixed = mix_final_medium(final_data, medium_data, {{meta::kSourceCheckpoint, "final+medium"}});
  ASSERT_EQ(mixed.size(), 100u);  // about one source
  EXPECT_TRUE(bit_identical(part(mixed, 0, 50), part(final_data, 0, 50))) << "first half: final";
  EXPECT_TRUE(bit_identical(part(mixed, 50, 100), part(medium_data, 0, 50))) << "second half: medium";
  EXPECT_EQ(mixed.metadata, (Metadata{{meta::kSourceCheckpoint, "final+medium"}}));
  EXPECT_EQ(split_episodes(mixed).size(), 5u + 10u);
  EXPECT_TRUE(bit_identical(mixed, mix_final_medium(final_data, medium_data, mixed.metadata))) << "deterministic";
}

TEST(DatasetMix, HalfStopsAtTheFirstEpisodeBoundaryPastHalf) {
  EXPECT_EQ(half_by_episodes_size(make_dataset(2, 1, {3, 4, 5})), 7u);  // 12 / 2 = 6 → after episode 2
  EXPECT_EQ(half_by_episodes_size(make_dataset(2, 1, {6, 6})), 6u);     // exactly half
  EXPECT_EQ(half_by_episodes_size(make_dataset(2, 1, {9, 1, 1})), 9u);  // one long episode is more than half
  EXPECT_EQ(half_by_episodes_size(make_dataset(2, 1, {2, 5}, 1, true)), 7u);  // partial tail counts as whole
  EXPECT_EQ(half_by_episodes_size(make_dataset(2, 1, {1})), 1u);
}

TEST(DatasetMix, UnequalSourcesEachContributeHalf) {
  const Dataset final_data = make_dataset(3, 1, {4, 4, 4, 4}, 1);  // 16 → 8
  const Dataset medium_data = make_dataset(3, 1, {3, 3, 3}, 2);    // 9 → 6
  const Dataset mixed = mix_final_medium(final_data, medium_data, {});
  EXPECT_EQ(mixed.size(), 14u);
  EXPECT_EQ(split_episodes(mixed).size(), 4u);
}

TEST(DatasetMix, ConcatenateClosesACutEpisodeWithATimeout) {
  const Dataset cut = make_dataset(2, 1, {2, 3}, 1, /*trailing_partial=*/true);
  const Dataset next = make_dataset(2, 1, {4}, 2);
  const Dataset joined = concatenate(cut, next, {});
  ASSERT_EQ(joined.size(), 9u);
  EXPECT_TRUE(joined.timeouts[4]);
  EXPECT_FALSE(joined.terminals[4]);
  EXPECT_EQ(split_episodes(joined).size(), 3u);
}

TEST(DatasetMix, ConcatenateRejectsOtherDimensions) {
  EXPECT_THROW(concatenate(make_dataset(2, 1, {3}), make_dataset(3, 1, {3}), {}), std::invalid_argument);
  EXPECT_THROW(slice(make_dataset(2, 1, {3}), 2, 4), std::out_of_range);
}

}  // namespace
}  // namespace rapid
