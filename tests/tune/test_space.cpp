// The space file: what it accepts and refuses (one line naming the field), and the candidates
// it draws: the defaults first, the same quantile of a shared key for every method, a method's
// own keys only for the methods that tune them, every value inside its range, and one candidate
// per stratum of each range.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "experiments/tune/space.hpp"

namespace rapid {
namespace {

using nlohmann::json;

json flow_like() {
  return {{"name", "s"},
          {"seeds", {50, 51, 52, 53, 54, 55}},
          {"candidates", 5},
          {"sampler_seed", 7},
          {"rungs", {1, 2}},
          {"trial_config", {{"final_eval_episodes", 4}}},
          {"keys",
           {{"actor_lr", {{"log_uniform", {1e-5, 1e-3}}}},
            {"batch_size", {{"choice", {32, 64}}}},
            {"epsilon", {{"uniform", {{"merge", {-0.5, 0.5}}, {"cut-in", {0.0, 0.1}}}}, {"algos", {"rapid-rl"}}}}}}};
}

std::string problem(const json& doc) {
  try {
    parse_space(doc, "x.json");
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(SearchSpace, CandidatesShareQuantilesAndStayInTheirRanges) {
  const SearchSpace s = parse_space(flow_like(), "x.json");
  EXPECT_TRUE(candidate_overrides(s, "merge", "rapid-rl", 0).empty());
  std::set<int> strata;
  for (int k = 1; k < s.candidates; ++k) {
    const json rapid = candidate_overrides(s, "merge", "rapid-rl", k);
    const json ddpg = candidate_overrides(s, "merge", "ddpg", k);
    EXPECT_EQ(rapid["actor_lr"], ddpg["actor_lr"]) << k;  // common random numbers
    EXPECT_EQ(rapid["batch_size"], ddpg["batch_size"]) << k;
    EXPECT_FALSE(ddpg.contains("epsilon"));
    const double lr = rapid["actor_lr"].get<double>(), eps = rapid["epsilon"].get<double>();
    EXPECT_GE(lr, 1e-5);
    EXPECT_LE(lr, 1e-3);
    EXPECT_GE(eps, -0.5);
    EXPECT_LE(eps, 0.5);
    const double cut_in = candidate_overrides(s, "cut-in", "rapid-rl", k)["epsilon"].get<double>();
    EXPECT_GE(cut_in, 0.0);
    EXPECT_LE(cut_in, 0.1);
    strata.insert(static_cast<int>(std::log(lr / 1e-5) / std::log(100.0) * (s.candidates - 1)));
  }
  EXPECT_EQ(strata.size(), static_cast<std::size_t>(s.candidates - 1));  // a Latin hypercube
  EXPECT_THROW(candidate_overrides(s, "lane-drop", "rapid-rl", 1), std::invalid_argument);  // no range there
  EXPECT_EQ(unit_seeds(s, true, 3, 2), (std::vector<std::uint64_t>{50, 51}));
  EXPECT_EQ(unit_seeds(s, false, 3, 2), (std::vector<std::uint64_t>{50, 51, 52, 53, 54, 55}));
  EXPECT_THROW(unit_seeds(s, false, 3, 3), std::invalid_argument);
  EXPECT_EQ(trial_overrides(s, "merge"), (json{{"final_eval_episodes", 4}}));
}

TEST(SearchSpace, BadFilesAreRefusedNamingTheField) {
  json d = flow_like();
  d["seeds"] = {50, 100};
  EXPECT_NE(problem(d).find("space x.json: seeds[1]: seed 100: seeds from 100 up are reserved"), std::string::npos) << problem(d);
  d = flow_like();
  d["rungs"] = {2, 2};
  EXPECT_NE(problem(d).find("rungs[1]: the units must increase"), std::string::npos);
  d = flow_like();
  d["keys"]["actor_lr"] = {{"log_uniform", {0.0, 1e-3}}};
  EXPECT_NE(problem(d).find("keys.actor_lr.log_uniform: a log-uniform range must be positive"), std::string::npos);
  d = flow_like();
  d["keys"]["tau"] = {{"uniform", {0.1, 0.01}}};
  EXPECT_NE(problem(d).find("keys.tau.uniform: expected lo < hi"), std::string::npos);
  d = flow_like();
  d["keys"]["inflow"] = {{"uniform", {1000, 2000}}};
  EXPECT_NE(problem(d).find("keys.inflow: a scenario key"), std::string::npos);
  d = flow_like();
  d["keys"]["epsilon"]["algos"] = {"ddpg"};
  EXPECT_NE(problem(d).find("keys.epsilon.algos: 'ddpg' does not read 'epsilon'"), std::string::npos);
  d = flow_like();
  d["trial_config"] = {{"actor_lr", 1e-4}};
  EXPECT_NE(problem(d).find("trial_config.actor_lr: expected a schedule key"), std::string::npos);
  d = flow_like();
  d["extra"] = 1;
  EXPECT_NE(problem(d).find("extra: unknown key"), std::string::npos);
}

}  // namespace
}  // namespace rapid
