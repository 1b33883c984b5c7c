// The driving reward's building blocks (SUMO-free).
#include <gtest/gtest.h>

#include "envs/driving_reward.hpp"

#include "core/rng.hpp"

namespace rapid::driving {
namespace {

TEST(DrivingReward, VelocityTermPeaksAtTheDesiredSpeed) {
  EXPECT_DOUBLE_EQ(velocity_term(25.0, 25.0), 1.0);
  EXPECT_DOUBLE_EQ(velocity_term(0.0, 25.0), 0.0);
  EXPECT_DOUBLE_EQ(velocity_term(12.5, 25.0), 0.5);
  EXPECT_DOUBLE_EQ(velocity_term(30.0, 25.0), 0.8);
  EXPECT_DOUBLE_EQ(velocity_term(60.0, 25.0), 0.0);
}

TEST(DrivingReward, IdmDesiredGap) {
  const IdmGap idm;
  // s* = s0 + v·T at equal speeds; closing in adds v·Δv / (2√(ab)).
  EXPECT_DOUBLE_EQ(idm.desired_gap(20.0, 0.0), 22.0);
  EXPECT_NEAR(idm.desired_gap(20.0, 5.0), 22.0 + 100.0 / (2.0 * std::sqrt(2.6 * 4.5)), 1e-12);
  // Falling behind never asks for less than s0.
  EXPECT_DOUBLE_EQ(idm.desired_gap(1.0, -20.0), 2.0);
  EXPECT_DOUBLE_EQ(idm.shortfall(30.0, 20.0, 0.0), 0.0);
  EXPECT_DOUBLE_EQ(idm.shortfall(11.0, 20.0, 0.0), 0.5);
  EXPECT_DOUBLE_EQ(idm.shortfall(0.0, 20.0, 0.0), 1.0);
}

// The reward as DrivingEnv computed it before reward_terms existed, spelled out again: the terms'
// total must be that value to the last bit (recording an episode must not change its rewards).
float historical_reward(const RewardWeights& w, const IdmGap& idm, const RewardInputs& in) {
  if (in.collision) return static_cast<float>(-w.collision);
  const double v = in.speed;
  double r = velocity_term(v, in.desired_speed) - w.offset;
  if (in.leader) r -= w.gap * idm.shortfall(in.leader_gap, v, v - in.leader_speed);
  if (in.changed_lane && in.follower) r -= w.gap * idm.shortfall(in.follower_gap, in.follower_speed, in.follower_speed - v);
  if (in.failed_lane_change) r -= w.failed_lane_change;
  return static_cast<float>(r);
}

TEST(DrivingReward, TermsSumToTheRewardBitForBit) {
  const IdmGap idm;
  Rng rng(5);
  for (const char* variant : {"short", "flow"}) {
    const RewardWeights w = reward_weights(variant);
    for (int i = 0; i < 20000; ++i) {
      RewardInputs in;
      in.speed = rng.uniform(0.0, 35.0);
      in.desired_speed = rng.uniform() < 0.5 ? 25.0 : rng.uniform(10.0, 30.0);
      in.leader = rng.uniform() < 0.7;
      in.leader_gap = rng.uniform(0.0, 100.0);
      in.leader_speed = rng.uniform(0.0, 35.0);
      in.follower = rng.uniform() < 0.7;
      in.follower_gap = rng.uniform(0.0, 100.0);
      in.follower_speed = rng.uniform(0.0, 35.0);
      in.collision = rng.uniform() < 0.05;
      in.changed_lane = rng.uniform() < 0.3;
      in.failed_lane_change = rng.uniform() < 0.2;
      const RewardTerms t = reward_terms(w, idm, in);
      const float reward = static_cast<float>(t.total);
      ASSERT_EQ(reward, historical_reward(w, idm, in)) << variant << " case " << i;
      // The documented reading of a trace: total = velocity − gap − follower − failed, or −collision.
      const double again = in.collision ? -t.collision : t.velocity - t.gap - t.follower - t.failed_lane_change;
      ASSERT_EQ(again, t.total);
      EXPECT_GE(t.gap, 0.0);
      EXPECT_GE(t.follower, 0.0);
      if (in.collision) {
        EXPECT_EQ(t.velocity + t.gap + t.follower + t.failed_lane_change, 0.0);
      }
    }
  }
}

TEST(DrivingReward, TermsNameWhatWasPenalised) {
  const IdmGap idm;
  const RewardWeights w = reward_weights("short");
  RewardInputs in;
  in.speed = 20.0;
  in.leader = true;
  in.leader_gap = 11.0;  // half of s* = 22 m at equal speeds
  in.leader_speed = 20.0;
  in.failed_lane_change = true;
  const RewardTerms t = reward_terms(w, idm, in);
  EXPECT_DOUBLE_EQ(t.velocity, 0.8);
  EXPECT_DOUBLE_EQ(t.gap, 0.5);
  EXPECT_EQ(t.follower, 0.0);  // no lane change: the follower is not charged
  EXPECT_DOUBLE_EQ(t.failed_lane_change, 0.3);
  EXPECT_EQ(t.collision, 0.0);
  in.collision = true;
  const RewardTerms c = reward_terms(w, idm, in);
  EXPECT_EQ(c.collision, 10.0);
  EXPECT_EQ(c.total, -10.0);
}

}  // namespace
}  // namespace rapid::driving
