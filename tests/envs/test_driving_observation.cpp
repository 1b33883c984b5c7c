// Observations: fixed size, every entry finite and in [-1, 1], for random driving; the registry.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/json_input.hpp"
#include "core/rng.hpp"
#include "envs/scenario_descriptor.hpp"
#include "tests/envs/driving_test_util.hpp"

namespace rapid {
namespace {

TEST(Registry, KnowsTheThreeScenariosAndPendulum) {
  // The built-ins are the folders of the build's networks with a descriptor, by name.
  const std::vector<std::string> expected = {"cut-in", "lane-drop", "merge", "pendulum"};
  EXPECT_EQ(env_names(), expected);
  for (const auto& name : expected) {
    auto env = make_env(name);
    EXPECT_EQ(env->name(), name);
  }
  EXPECT_THROW(make_env("highway"), std::invalid_argument);
}

TEST(DrivingObservation, ADescriptorsNeighbourLanesChooseTheBlocksItHolds) {
  // merge's own descriptor with only the ego's lane observed: its 2 + 5 + 1 entries are the
  // built-in's 0-1, 7-11 (the current lane) and 17 (the feature), decision by decision.
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(network_dir()) / "merge";
  nlohmann::json d = read_json_input((dir / "scenario.json").string());
  for (auto& [variant, files] : d["networks"].items())
    for (const char* key : {"net", "routes"}) files[key] = (dir / files[key].get<std::string>()).string();
  d["additional_files"] = {(dir / d["additional_files"][0].get<std::string>()).lexically_normal().string()};
  d["observation"]["neighbours"] = {"current"};
  const fs::path file = fs::path(::testing::TempDir()) / ("merge-current-lane-" + std::to_string(::getpid()) + ".json");
  std::ofstream(file) << d.dump();

  auto full = make_env("merge");
  auto current = make_env(file.string());
  ASSERT_EQ(current->obs_dim(), 8);
  Vec a(full->obs_dim()), b(current->obs_dim()), action(2);
  Rng rng(3);
  for (int episode = 0; episode < 2; ++episode) {
    // One process has one simulation: step the two envs in turn, each from its own reset.
    std::vector<Vec> seen_full, seen_current;
    std::vector<Vec> actions;
    full->reset(episode + 1, a);
    seen_full.push_back(a);
    for (bool done = false; !done && seen_full.size() < 200;) {
      action << static_cast<float>(rng.uniform(-1, 1)), static_cast<float>(rng.uniform(-1, 1));
      actions.push_back(action);
      const StepResult r = full->step(action, a);
      seen_full.push_back(a);
      done = r.terminated || r.truncated;
    }
    current->reset(episode + 1, b);
    seen_current.push_back(b);
    for (const Vec& act : actions) {
      current->step(act, b);
      seen_current.push_back(b);
    }
    ASSERT_EQ(seen_full.size(), seen_current.size());
    for (std::size_t t = 0; t < seen_full.size(); ++t) {
      const Vec& f = seen_full[t];
      const Vec& c = seen_current[t];
      EXPECT_EQ(c[0], f[0]);
      EXPECT_EQ(c[1], f[1]);
      for (int k = 0; k < 5; ++k) EXPECT_EQ(c[2 + k], f[7 + k]) << "t " << t << " entry " << k;
      EXPECT_EQ(c[7], f[17]) << "t " << t;
    }
  }
  fs::remove(file);
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
    EXPECT_NE(what.find("unknown scenario 'merge'"), std::string::npos) << what;
    EXPECT_NE(what.find("no built-in scenario in /nonexistent/networks"), std::string::npos) << what;
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
