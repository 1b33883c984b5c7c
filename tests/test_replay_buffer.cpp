#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

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

namespace {
// Adds transitions with the given rewards and episode ends ('.' goes on, 'T' terminal, 'O' timeout).
void add_rewards(ReplayBuffer& buf, const std::vector<float>& rewards, const std::string& ends) {
  const Vec s = Vec::Zero(buf.obs_dim()), a = Vec::Zero(buf.act_dim());
  for (std::size_t i = 0; i < rewards.size(); ++i) buf.add(s, a, rewards[i], s, ends[i] == 'T', ends[i] == 'O');
}

std::vector<float> mean_returns(const ReplayBuffer& buf) {
  std::vector<float> out;
  for (std::size_t i = 0; i < buf.size(); ++i) out.push_back(buf.mean_return(i));
  return out;
}
}  // namespace

// Ḡ_t is the mean of r_t … r_{t+k−1}, the window cut at the episode's end, whichever way it ends.
TEST(ReturnWindow, MeanOverTheWindowCutAtTerminalsAndTimeouts) {
  ReplayBuffer buf(1, 1, 100, /*return_window=*/3);
  add_rewards(buf, {1, 2, 3, 4, 10, 20, 30, 100, 200}, "...T.O..T");
  EXPECT_EQ(mean_returns(buf), (std::vector<float>{
                                   (1 + 2 + 3) / 3.0f, (2 + 3 + 4) / 3.0f, (3 + 4) / 2.0f, 4,  // terminal at 4
                                   (10 + 20) / 2.0f, 20,                                      // timeout at 20
                                   (30 + 100 + 200) / 3.0f, (100 + 200) / 2.0f, 200}));
  Batch batch;
  batch.resize(1, 1, 200);
  Rng rng(3);
  buf.sample_into(rng, batch, 0, batch.size());
  std::map<float, float> ret_of_reward;  // the rewards are distinct
  for (std::size_t i = 0; i < buf.size(); ++i) ret_of_reward[buf.reward(i)] = buf.mean_return(i);
  for (int c = 0; c < batch.size(); ++c)  // Ḡ travels with its transition
    EXPECT_EQ(batch.ret[c], ret_of_reward.at(batch.rew[c])) << "column " << c;
}

TEST(ReturnWindow, WindowOneIsTheReward) {
  ReplayBuffer buf(1, 1, 10);
  EXPECT_EQ(buf.return_window(), 1);
  add_rewards(buf, {0.3f, -1.7f, 2.5f, 0.1f}, "..T.");
  EXPECT_EQ(mean_returns(buf), (std::vector<float>{0.3f, -1.7f, 2.5f, 0.1f}));
}

// The last transitions of an episode that has not ended (or of data that stops mid-episode) have
// the mean of the rewards they have so far, and complete their windows as the episode goes on.
TEST(ReturnWindow, AnUnfinishedWindowHasTheMeanSoFar) {
  ReplayBuffer buf(1, 1, 100, 4);
  add_rewards(buf, {2, 4, 6}, "...");
  EXPECT_EQ(mean_returns(buf), (std::vector<float>{4, 5, 6}));
  add_rewards(buf, {8, 10}, "..");
  EXPECT_EQ(mean_returns(buf), (std::vector<float>{5, 7, 8, 9, 10}));
}

// Overwriting the oldest slots neither disturbs the windows of the transitions kept nor lets a new
// transition's reward reach the one it replaced.
TEST(ReturnWindow, RingOverwriteKeepsTheWindowsRight) {
  ReplayBuffer buf(1, 1, 4, 3);
  add_rewards(buf, {1, 2, 3, 4, 5, 6, 7}, "..T....");
  ASSERT_EQ(buf.size(), 4u);
  EXPECT_EQ(buf.reward(0), 4.0f);
  EXPECT_EQ(mean_returns(buf), (std::vector<float>{5, 6, 6.5f, 7}));
  // A window longer than the buffer: the oldest kept transition holds the mean of what is kept after it.
  ReplayBuffer small(1, 1, 3, 10);
  add_rewards(small, {1, 2, 3, 4, 5}, ".....");
  EXPECT_EQ(mean_returns(small), (std::vector<float>{4, 4.5f, 5}));
}

TEST(ReturnWindow, AWindowBelowOneIsRefused) {
  EXPECT_THROW(ReplayBuffer(1, 1, 4, 0), std::invalid_argument);
}
