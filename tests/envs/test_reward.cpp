// The driving reward's building blocks (SUMO-free).
#include <gtest/gtest.h>

#include "envs/driving_reward.hpp"

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

}  // namespace
}  // namespace rapid::driving
