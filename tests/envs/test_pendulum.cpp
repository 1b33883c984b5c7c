// The SUMO-free pendulum: reward formula, dynamics and the 200-step time limit.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "envs/pendulum.hpp"

namespace rapid {
namespace {

TEST(Pendulum, RewardAtAKnownState) {
  PendulumEnv env;
  Vec obs(3), u(1);
  env.reset(1, obs);
  env.set_state(0.5, 1.0);
  u << 0.25f;  // torque 0.5
  const StepResult r = env.step(u, obs);
  EXPECT_NEAR(r.reward, -(0.25 + 0.1 * 1.0 + 0.001 * 0.25), 1e-6);
}

TEST(Pendulum, UprightAndHangingAtRestStayPut) {
  PendulumEnv env;
  Vec obs(3), u = Vec::Zero(1);
  env.reset(1, obs);
  env.set_state(0.0, 0.0);
  for (int i = 0; i < 50; ++i) env.step(u, obs);
  EXPECT_NEAR(env.theta(), 0.0, 1e-12);
  env.set_state(std::numbers::pi, 0.0);
  for (int i = 0; i < 50; ++i) env.step(u, obs);
  EXPECT_NEAR(std::cos(env.theta()), -1.0, 1e-6);
}

TEST(Pendulum, FallsAwayFromUprightAndObservationIsBounded) {
  PendulumEnv env;
  Vec obs(3), u = Vec::Zero(1);
  env.reset(1, obs);
  env.set_state(0.1, 0.0);
  env.step(u, obs);
  EXPECT_GT(env.theta_dot(), 0.0);  // gravity pulls it further from upright
  for (int i = 0; i < 100; ++i) {
    env.step(u, obs);
    EXPECT_LE(obs.cwiseAbs().maxCoeff(), 1.0f);
  }
}

TEST(Pendulum, TruncatesAfter200Steps) {
  PendulumEnv env;
  Vec obs(3), u = Vec::Zero(1);
  env.reset(3, obs);
  for (int t = 1; t <= 200; ++t) {
    const StepResult r = env.step(u, obs);
    EXPECT_FALSE(r.terminated);
    EXPECT_EQ(r.truncated, t == 200) << "step " << t;
  }
}

}  // namespace
}  // namespace rapid
