#include <gtest/gtest.h>

#include "core/replay_buffer.hpp"

using namespace rapid;

namespace {
// Fills `buf` with `n` transitions whose every field encodes `base + i`.
void fill(ReplayBuffer& buf, int n, float base) {
  Vec s(buf.obs_dim()), a(buf.act_dim()), s2(buf.obs_dim());
  for (int i = 0; i < n; ++i) {
    s.setConstant(base + i);
    a.setConstant(base + i);
    s2.setConstant(base + i + 0.5f);
    buf.add(s, a, base + i, s2, /*terminal=*/i % 3 == 0, /*timeout=*/i % 5 == 0);
  }
}
}  // namespace

TEST(ReplayBuffer, RingOverwritesOldest) {
  ReplayBuffer buf(2, 1, 4);
  fill(buf, 6, 0.0f);
  EXPECT_EQ(buf.size(), 4u);
  EXPECT_EQ(buf.reward(0), 2.0f);  // 0 and 1 were overwritten
  EXPECT_EQ(buf.reward(3), 5.0f);
  EXPECT_EQ(buf.next_obs(0)[0], 2.5f);
  EXPECT_TRUE(buf.terminal(1));  // transition 3
  EXPECT_TRUE(buf.timeout(3));   // transition 5
}

TEST(ReplayBuffer, SamplesOnlyStoredTransitionsUniformly) {
  ReplayBuffer buf(3, 2, 100);
  fill(buf, 10, 0.0f);
  Batch batch;
  batch.resize(3, 2, 1000);
  Rng rng(5);
  std::vector<int> counts(10, 0);
  for (int rep = 0; rep < 20; ++rep) {
    buf.sample_into(rng, batch, 0, batch.size());
    for (int c = 0; c < batch.size(); ++c) {
      const float r = batch.rew[c];
      ASSERT_GE(r, 0.0f);
      ASSERT_LE(r, 9.0f);
      ASSERT_EQ(batch.obs(0, c), r);  // fields of one transition stay together
      ASSERT_EQ(batch.next_obs(2, c), r + 0.5f);
      // Transition 5 is a timeout only: not a terminal, so the critic target bootstraps through it.
      ASSERT_EQ(batch.not_terminal[c], static_cast<int>(r) % 3 == 0 ? 0.0f : 1.0f);
      ++counts[static_cast<int>(r)];
    }
  }
  for (int k = 0; k < 10; ++k) EXPECT_NEAR(counts[k], 2000, 200) << "transition " << k;
}

TEST(SymmetricSampler, HalfPriorHalfOnline) {
  ReplayBuffer prior(2, 1, 50), online(2, 1, 50);
  fill(prior, 50, 1000.0f);
  fill(online, 3, 0.0f);
  SymmetricSampler sampler(&prior, &online);
  Rng rng(1);
  for (int b : {2, 64, 256, 7}) {
    Batch batch;
    batch.resize(2, 1, b);
    sampler.sample(rng, batch);
    EXPECT_EQ(batch.prior_count, b / 2);
    for (int c = 0; c < b; ++c) {
      const bool from_prior = batch.rew[c] >= 1000.0f;
      EXPECT_EQ(from_prior, c < b / 2) << "column " << c << " of a batch of " << b;
    }
  }
}

TEST(SymmetricSampler, WithoutPriorTheWholeBatchIsOnline) {
  ReplayBuffer online(2, 1, 10);
  fill(online, 5, 0.0f);
  SymmetricSampler sampler(nullptr, &online);
  Batch batch;
  batch.resize(2, 1, 16);
  Rng rng(1);
  sampler.sample(rng, batch);
  EXPECT_EQ(batch.prior_count, 0);
  EXPECT_LE(batch.rew.maxCoeff(), 4.0f);
}

TEST(ReplayBuffer, EmptyBufferCannotBeSampled) {
  ReplayBuffer buf(2, 1, 4);
  Batch batch;
  batch.resize(2, 1, 4);
  Rng rng(1);
  EXPECT_THROW(buf.sample_into(rng, batch, 0, 4), std::logic_error);
}
