// The ego's controls and the episode's end: collisions, lane changes, failed lane changes,
// truncation at the horizon.
#include <gtest/gtest.h>

#include "tests/envs/driving_test_util.hpp"

namespace rapid {
namespace {

Vec act(float accel, float lane) {
  Vec a(2);
  a << accel, lane;
  return a;
}

TEST(DrivingControl, FullThrottleIntoASlowerLeaderIsACollision) {
  auto env = test::make_driving("lane-drop");
  Vec obs(env->obs_dim());
  // An entry lane that continues (lane 0 ends at the drop: that crash would not need a leader).
  std::uint64_t seed = 1;
  for (env->reset(seed, obs); env->ego().lane == 0;) env->reset(++seed, obs);
  const double penalty = env->reward_weights().collision;
  for (int t = 0; t < env->horizon(); ++t) {
    const DrivingEnv::EgoState before = env->ego();
    const StepResult r = env->step(act(1.0f, 0.0f), obs);
    if (r.terminated) {
      EXPECT_TRUE(r.info.collision);
      EXPECT_FALSE(r.truncated);
      EXPECT_EQ(r.reward, static_cast<float>(-penalty));
      ASSERT_TRUE(before.leader[1].present);
      EXPECT_LT(before.leader[1].speed, before.speed);
      return;
    }
    EXPECT_FALSE(r.info.collision);
  }
  FAIL() << "full throttle through the lane-drop queue never collided";
}

TEST(DrivingControl, LeftAndRightCommandsMoveTheEgoOneLane) {
  auto env = test::make_driving("cut-in");
  Vec obs(env->obs_dim());
  const int interval = env->settings().lane_change_interval;
  int tested = 0;
  for (std::uint64_t seed = 1; seed <= 30 && tested < 3; ++seed) {
    env->reset(seed, obs);
    const auto& e = env->ego();
    // The middle lane with room on the left: nobody within 20 m either way.
    if (e.lane != 1 || (e.leader[0].present && e.leader[0].gap < 20) ||
        (e.follower[0].present && e.follower[0].gap < 20))
      continue;
    ++tested;
    const int lane = e.global_lane;
    StepResult r = env->step(act(0.0f, 1.0f), obs);
    ASSERT_FALSE(r.terminated);
    EXPECT_EQ(env->ego().global_lane, lane + 1);
    EXPECT_EQ(r.info.lane_changes, 1);
    EXPECT_FALSE(r.info.lane_change_failed);
    EXPECT_EQ(obs[1], -1.0f);  // the minimum interval has started
    // Within the minimum interval a second change is refused and penalised.
    r = env->step(act(0.0f, -1.0f), obs);
    EXPECT_TRUE(r.info.lane_change_failed);
    EXPECT_EQ(env->ego().global_lane, lane + 1);
    for (int k = 1; k < interval; ++k) env->step(act(0.0f, 0.0f), obs);
    EXPECT_EQ(obs[1], 1.0f);
    const bool right_free = !(env->ego().leader[2].present && env->ego().leader[2].gap < 10) &&
                            !(env->ego().follower[2].present && env->ego().follower[2].gap < 10);
    if (!right_free) continue;
    r = env->step(act(0.0f, -1.0f), obs);
    EXPECT_EQ(env->ego().global_lane, lane);
    EXPECT_EQ(r.info.lane_changes, 1);
  }
  EXPECT_GT(tested, 0) << "no seed put the ego in the middle lane with room on its left";
}

TEST(DrivingControl, ChangingIntoAMissingLaneIsPenalisedAndDoesNothing) {
  auto env = test::make_driving("merge");
  Vec kept(env->obs_dim()), failed(env->obs_dim());
  env->reset(3, kept);
  ASSERT_EQ(env->ego_edge(), "ramp");  // one lane: neither left nor right exists
  const StepResult keep = env->step(act(0.2f, 0.0f), kept);
  for (float dir : {1.0f, -1.0f}) {
    env->reset(3, failed);
    const StepResult r = env->step(act(0.2f, dir), failed);
    EXPECT_TRUE(r.info.lane_change_failed);
    EXPECT_EQ(r.info.lane_changes, 0);
    EXPECT_EQ(env->ego_edge(), "ramp");
    EXPECT_NEAR(keep.reward - r.reward, env->reward_weights().failed_lane_change, 1e-6);
    EXPECT_TRUE(kept.isApprox(failed, 0.0f)) << "a refused command changed the traffic";
  }
}

TEST(DrivingControl, HorizonTruncatesWithoutTerminating) {
  auto env = make_env("merge");
  env->set_builtin_driver(true);  // SUMO's driver does not crash
  Vec obs(env->obs_dim()), action = Vec::Zero(2);
  env->reset(8, obs);
  int t = 0;
  StepResult r;
  do {
    r = env->step(action, obs);
    ++t;
  } while (!r.terminated && !r.truncated);
  EXPECT_EQ(t, env->horizon());
  EXPECT_TRUE(r.truncated);
  EXPECT_FALSE(r.terminated);
  EXPECT_THROW(env->step(action, obs), std::logic_error);
}

TEST(DrivingControl, AccelerationCommandIsApplied) {
  auto env = test::make_driving("cut-in");
  Vec obs(env->obs_dim());
  env->reset(2, obs);
  const double v0 = env->ego().speed;
  const double dt = env->settings().action_repeat * env->scenario().step_length;
  env->step(act(-0.5f, 0.0f), obs);
  EXPECT_NEAR(env->ego().speed, std::max(0.0, v0 - 0.5 * env->scenario().max_accel * dt), 1e-6);
}

}  // namespace
}  // namespace rapid
