// Building datasets transition by transition or from a replay buffer, and loading one as the
// prior buffer.
#include <gtest/gtest.h>

#include "core/dataset.hpp"
#include "core/dataset_mix.hpp"
#include "tests/datasets/dataset_fixtures.hpp"

namespace rapid {
namespace {

using testing::bit_identical;
using testing::make_dataset;

TEST(DatasetBuffer, BuilderCollectsTransitionsInOrder) {
  const Dataset source = make_dataset(3, 2, {4, 3});
  DatasetBuilder builder(3, 2);
  builder.reserve(2);  // growing past the reservation is fine
  for (std::size_t i = 0; i < source.size(); ++i) {
    const auto c = static_cast<Eigen::Index>(i);
    builder.add(source.observations.col(c), source.actions.col(c), source.rewards[c],
                source.next_observations.col(c), source.terminals[i], source.timeouts[i]);
  }
  EXPECT_EQ(builder.size(), 7u);
  EXPECT_TRUE(bit_identical(builder.finish(source.metadata), source));
  EXPECT_EQ(builder.size(), 0u);
  EXPECT_TRUE(builder.finish().empty());
}

TEST(DatasetBuffer, BuilderRejectsWrongSizes) {
  DatasetBuilder builder(3, 2);
  EXPECT_THROW(builder.add(Vec::Zero(3), Vec::Zero(1), 0.0f, Vec::Zero(3), false, false), std::invalid_argument);
  EXPECT_THROW(DatasetBuilder(0, 2), std::invalid_argument);
}

TEST(DatasetBuffer, PriorBufferHoldsTheWholeDatasetInOrder) {
  const Dataset d = make_dataset(5, 2, {6, 4, 3});
  const ReplayBuffer buffer = make_prior_buffer(d);
  EXPECT_EQ(buffer.capacity(), d.size());
  EXPECT_EQ(buffer.size(), d.size());
  EXPECT_TRUE(bit_identical(dataset_from_buffer(buffer, d.metadata), d));
  EXPECT_THROW(make_prior_buffer(make_dataset(5, 2, {})), std::invalid_argument);
}

// The prior buffer's mean rewards over the window (Batch::ret) are those of the dataset's own
// episodes, computed here straight from their definition; the trailing episode without an end is
// cut where the data stops.
TEST(DatasetBuffer, PriorBufferComputesReturnsWithinEachEpisode) {
  const int window = 3;
  for (const bool trailing_partial : {false, true}) {
    SCOPED_TRACE(trailing_partial);
    const Dataset d = make_dataset(2, 1, {5, 1, 4}, 7, trailing_partial);
    EXPECT_TRUE(d.has_episode_ends());
    const ReplayBuffer buffer = make_prior_buffer(d, window);
    for (std::size_t t = 0; t < d.size(); ++t) {
      float sum = 0;
      int k = 0;
      for (std::size_t j = t; j < d.size() && k < window; ++j) {
        sum += d.rewards[static_cast<Eigen::Index>(j)];
        ++k;
        if (d.ends_episode(j)) break;
      }
      EXPECT_EQ(buffer.mean_return(t), sum / static_cast<float>(k)) << "transition " << t;
    }
  }
  Dataset unbroken = make_dataset(2, 1, {4}, 7, /*trailing_partial=*/true);
  EXPECT_FALSE(unbroken.has_episode_ends());
}

TEST(DatasetBuffer, FromAWrappedRingBufferOldestFirst) {
  const Dataset d = make_dataset(2, 1, {3, 5});
  ReplayBuffer ring(2, 1, 5);
  for (std::size_t i = 0; i < d.size(); ++i) {
    const auto c = static_cast<Eigen::Index>(i);
    ring.add(d.observations.col(c), d.actions.col(c), d.rewards[c], d.next_observations.col(c), d.terminals[i],
             d.timeouts[i]);
  }
  Dataset last_five = slice(d, 3, 8);  // what a ring of 5 keeps of 8 transitions
  last_five.metadata.clear();
  EXPECT_TRUE(bit_identical(dataset_from_buffer(ring), last_five));
}

}  // namespace
}  // namespace rapid
