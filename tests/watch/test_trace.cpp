// Recording an episode (Env::record, docs/traces.md) in this process: the same seed writes the same
// bytes, recording changes nothing about the episode, the rewards and their terms add up, and the
// road is the scenario's real geometry.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>

#include "core/rng.hpp"
#include "envs/driving_env.hpp"
#include "envs/env.hpp"
#include "envs/trace.hpp"

namespace rapid {
namespace {

class Recording : public ::testing::TestWithParam<std::string> {};

struct Episode {
  std::vector<float> rewards, obs;
  double ret = 0;
};

// One episode of random actions (drawn from `seed`), recorded into `trace` when given.
Episode run(Env& env, std::uint64_t seed, Trace* trace, int max_steps = 60) {
  env.record(trace);
  Rng rng(seed);
  Vec obs(env.obs_dim()), action(env.act_dim());
  Episode ep;
  env.reset(seed, obs);
  ep.obs.assign(obs.data(), obs.data() + obs.size());
  for (int t = 0; t < max_steps; ++t) {
    for (int i = 0; i < action.size(); ++i) action[i] = static_cast<float>(rng.uniform(-1.0, 1.0));
    const StepResult r = env.step(action, obs);
    ep.rewards.push_back(r.reward);
    ep.ret += r.reward;
    ep.obs.insert(ep.obs.end(), obs.data(), obs.data() + obs.size());
    if (r.terminated || r.truncated) break;
  }
  env.record(nullptr);
  return ep;
}

TEST_P(Recording, SameSeedSameBytes) {
  Trace a, b, c;
  auto env = make_env(GetParam());
  run(*env, 7, &a);
  auto fresh = make_env(GetParam());
  run(*fresh, 7, &b);
  run(*fresh, 8, &c);
  const std::string ja = trace_to_json(a);
  EXPECT_EQ(ja, trace_to_json(b));
  EXPECT_NE(ja, trace_to_json(c));
  EXPECT_EQ(ja.find("nan"), std::string::npos);
}

TEST_P(Recording, ChangesNothingAboutTheEpisode) {
  auto env = make_env(GetParam());
  Trace trace;
  const Episode recorded = run(*env, 9, &trace);
  const Episode plain = run(*env, 9, nullptr);
  ASSERT_EQ(recorded.rewards.size(), plain.rewards.size());
  EXPECT_EQ(0, std::memcmp(recorded.rewards.data(), plain.rewards.data(), plain.rewards.size() * sizeof(float)));
  ASSERT_EQ(recorded.obs.size(), plain.obs.size());
  EXPECT_EQ(0, std::memcmp(recorded.obs.data(), plain.obs.data(), plain.obs.size() * sizeof(float)));
  ASSERT_EQ(trace.episodes.size(), 1u) << "an episode run after record(nullptr) was recorded";
}

TEST_P(Recording, RewardsAndTermsAddUpToTheReturn) {
  auto env = make_env(GetParam());
  Trace trace;
  const Episode ep = run(*env, 10, &trace, 150);
  ASSERT_EQ(trace.episodes.size(), 1u);
  const TraceEpisode& rec = trace.episodes[0];
  ASSERT_EQ(rec.decisions.size(), ep.rewards.size());
  double sum = 0;
  for (std::size_t t = 0; t < rec.decisions.size(); ++t) {
    const TraceDecision& d = rec.decisions[t];
    EXPECT_EQ(d.t, static_cast<int>(t));
    EXPECT_EQ(d.reward, ep.rewards[t]);
    const driving::RewardTerms& k = d.terms;
    const double total = d.collision ? -k.collision : k.velocity - k.gap - k.follower - k.failed_lane_change;
    EXPECT_EQ(static_cast<float>(total), d.reward) << "decision " << t;
    sum += d.reward;
  }
  EXPECT_EQ(sum, ep.ret);
  EXPECT_EQ(rec.ret, ep.ret);
  // And so in the JSON: every reward reads back exactly, and so does the return.
  const nlohmann::json j = nlohmann::json::parse(trace_to_json(trace));
  double parsed = 0;
  for (const auto& d : j["episodes"][0]["decisions"]) parsed += d["reward"].get<float>();
  EXPECT_EQ(parsed, ep.ret);
  EXPECT_EQ(j["episodes"][0]["return"].get<double>(), ep.ret);
}

TEST_P(Recording, VehiclesWithinTheSensingRangeOnTheRoad) {
  auto env = make_env(GetParam());
  Trace trace;
  run(*env, 11, &trace, 40);
  const TraceEpisode& ep = trace.episodes.at(0);
  std::size_t seen = 0;
  for (const TraceDecision& d : ep.decisions) {
    EXPECT_EQ(d.state.ego.id, "ego");
    for (const TraceVehicle& v : d.state.vehicles) {
      EXPECT_NE(v.id, "ego");
      EXPECT_LE(std::hypot(v.x - d.state.ego.x, v.y - d.state.ego.y), trace.sensing_range + 1e-9);
      EXPECT_GT(v.length, 0);
      EXPECT_GT(v.width, 0);
      const std::string edge = v.lane.substr(0, v.lane.rfind('_'));
      bool on_road = false;
      for (const TraceEdge& e : trace.road) on_road = on_road || e.id == edge;
      EXPECT_TRUE(on_road) << v.id << " on " << v.lane;
    }
    seen += d.state.vehicles.size();
  }
  EXPECT_GT(seen, 0u) << "no traffic recorded around the ego";
  EXPECT_EQ(trace.scenario, GetParam());
}

INSTANTIATE_TEST_SUITE_P(DrivingScenarios, Recording, ::testing::Values("lane-drop", "cut-in", "merge"),
                         [](const auto& info) {
                           std::string name = info.param;
                           for (char& c : name)
                             if (c == '-') c = '_';
                           return name;
                         });

TEST(Recording, MergeRoadHasItsAngledRamp) {
  auto env = make_env("merge");
  Trace trace;
  run(*env, 1, &trace, 2);
  const TraceEdge* ramp = nullptr;
  for (const TraceEdge& e : trace.road)
    if (e.id == "ramp") ramp = &e;
  ASSERT_NE(ramp, nullptr);
  ASSERT_EQ(ramp->lanes.size(), 1u);
  const auto& shape = ramp->lanes[0].shape;
  ASSERT_GE(shape.size(), 2u);
  // The ramp climbs towards the main road: real x/y shapes, not a straightened road.
  EXPECT_GT(std::abs(shape.back()[1] - shape.front()[1]), 20.0);
  EXPECT_EQ(trace.road.size(), 4u);
  EXPECT_FALSE(trace.junctions.empty());
  EXPECT_EQ(trace.episodes[0].start.ego.lane, "ramp_0");
}

TEST(Recording, EpisodesAppendInOrder) {
  auto env = make_env("cut-in");
  Trace trace;
  env->record(&trace);
  Vec obs(env->obs_dim()), action = Vec::Zero(env->act_dim());
  for (std::uint64_t seed : {3u, 4u}) {
    env->reset(seed, obs);
    env->step(action, obs);
  }
  ASSERT_EQ(trace.episodes.size(), 2u);
  EXPECT_EQ(trace.episodes[0].index, 0);
  EXPECT_EQ(trace.episodes[1].index, 1);
  EXPECT_EQ(trace.episodes[1].env_seed, 4u);
  EXPECT_EQ(trace.episodes[1].decisions.size(), 1u);
  ASSERT_TRUE(trace.episodes[1].decisions[0].action.has_value());
}

TEST(Recording, SumoDriverHasNoAction) {
  auto env = make_env("merge");
  env->set_builtin_driver(true);
  Trace trace;
  run(*env, 2, &trace, 3);
  for (const TraceDecision& d : trace.episodes.at(0).decisions) EXPECT_FALSE(d.action.has_value());
  EXPECT_NE(trace_to_json(trace).find("\"action\":null"), std::string::npos);
}

TEST(Recording, PendulumHasNothingToRecord) {
  auto env = make_env("pendulum");
  Trace trace;
  EXPECT_THROW(env->record(&trace), std::invalid_argument);
}

}  // namespace
}  // namespace rapid
