// Observations: fixed size, every entry finite and in [-1, 1], for random driving; the registry.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "core/rng.hpp"
#include "tests/envs/driving_test_util.hpp"

namespace rapid {
namespace {

TEST(Registry, KnowsTheThreeScenariosAndPendulum) {
  const std::vector<std::string> expected = {"lane-drop", "cut-in", "merge", "pendulum"};
  EXPECT_EQ(env_names(), expected);
  for (const auto& name : expected) {
    auto env = make_env(name);
    EXPECT_EQ(env->name(), name);
  }
  EXPECT_THROW(make_env("highway"), std::invalid_argument);
}

TEST(DrivingObservation, EveryEntryFiniteAndInRangeUnderRandomActions) {
  for (const auto& name : test::driving_scenarios()) {
    auto env = make_env(name);
    EXPECT_EQ(env->act_dim(), 2);
    Rng rng(5);
    Vec obs(env->obs_dim()), action(2);
    for (int episode = 0; episode < 3; ++episode) {
      obs.setConstant(NAN);
      env->reset(100 + episode, obs);
      for (int t = 0;; ++t) {
        for (int i = 0; i < obs.size(); ++i) {
          ASSERT_TRUE(std::isfinite(obs[i])) << name << " entry " << i << " step " << t;
          ASSERT_LE(std::abs(obs[i]), 1.0f) << name << " entry " << i << " step " << t;
        }
        action << static_cast<float>(rng.uniform(-1.5, 1.5)), static_cast<float>(rng.uniform(-1.5, 1.5));
        const StepResult r = env->step(action, obs);
        ASSERT_TRUE(std::isfinite(r.reward));
        if (r.terminated || r.truncated) break;
      }
    }
  }
}

TEST(DrivingObservation, GapEntriesMatchTheLeaderAndFollower) {
  auto env = test::make_driving("lane-drop");
  env->set_builtin_driver(true);
  Vec obs(env->obs_dim()), action = Vec::Zero(2);
  env->reset(4, obs);
  for (int t = 0; t < 60; ++t) env->step(action, obs);
  const auto& e = env->ego();
  const double range = env->scenario().sensing_range;
  // Current lane: entries 7-10.
  if (e.leader[1].present) {
    EXPECT_NEAR(obs[7], e.leader[1].gap / range, 1e-6);
    EXPECT_GT(e.leader[1].gap, 2.0);  // SUMO's driver keeps at least its minGap
  } else {
    EXPECT_EQ(obs[7], 1.0f);
  }
  if (e.follower[1].present) {
    EXPECT_NEAR(obs[9], -e.follower[1].gap / range, 1e-6);
  }
  EXPECT_NEAR(obs[0], 2.0 * e.speed / env->scenario().speed_norm - 1.0, 1e-6);
}

TEST(DrivingErrors, MissingNetworkIsAClearError) {
  // The built networks and the descriptors beside them are found when the env is made.
  setenv("RAPID_NETWORK_DIR", "/nonexistent/networks", 1);
  try {
    make_env("merge");
    ADD_FAILURE() << "making an env without its network did not throw";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("/nonexistent/networks/merge/scenario.json"), std::string::npos) << what;
    EXPECT_NE(what.find("build the 'rapid_networks' target or set RAPID_NETWORK_DIR"), std::string::npos) << what;
  }
  unsetenv("RAPID_NETWORK_DIR");
}

TEST(DrivingErrors, OneSimulationPerProcessIsExplicit) {
  auto a = make_env("cut-in");
  auto b = make_env("merge");
  Vec oa(a->obs_dim()), ob(b->obs_dim()), action = Vec::Zero(2);
  a->reset(1, oa);
  a->step(action, oa);
  b->reset(1, ob);  // takes libsumo's one simulation over
  b->step(action, ob);
  EXPECT_THROW(a->step(action, oa), std::runtime_error);
  a->reset(2, oa);  // and a reset takes it back
  EXPECT_NO_THROW(a->step(action, oa));
}

}  // namespace
}  // namespace rapid
