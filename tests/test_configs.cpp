// The config key table (experiments/run/config_keys.cpp) against everything that must agree with it:
// every scenario's config file, the key table of docs/algorithms.md and the ε table of
// docs/scenarios.md; and overrides checked by key, type, value and scenario.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "envs/env.hpp"
#include "envs/scenario_settings.hpp"
#include "algos/rapid_rl_return.hpp"
#include "algos/registry.hpp"
#include "algos/rlpd_sac.hpp"
#include "algos/td3_bc.hpp"
#include "experiments/run/job.hpp"
#include "experiments/run/run_config.hpp"

using namespace rapid;

namespace {

std::string read_doc(const std::string& name) {
  std::ifstream in(std::string(RAPID_SOURCE_DIR) + "/docs/" + name);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// (profile, scenario) for every built-in scenario's config in every profile it has: the short
// profile's scenarios, then the flow profile's.
std::vector<std::pair<std::string, std::string>> config_files() {
  std::vector<std::pair<std::string, std::string>> files;
  for (const std::string& p : config_profiles())
    for (const std::string& s : env_names()) {
      try {
        check_profile(p, s);
      } catch (const std::invalid_argument&) {
        continue;  // no such profile for this scenario (the pendulum's flow)
      }
      files.emplace_back(p, s);
    }
  return files;
}

// The key table as docs/algorithms.md must show it: one row per key, one value column per config
// file (a scenario key a short file leaves out shows the scenario's built-in value, an optional
// key a file leaves out shows "absent").
std::string key_table_markdown() {
  std::ostringstream out;
  const auto files = config_files();
  out << "| key | configures | accepts | meaning |";
  for (const auto& [p, s] : files) out << " " << (p == kDefaultProfile ? "" : p + " ") << s << " |";
  out << "\n| --- | --- | --- | --- |";
  for (std::size_t i = 0; i < files.size(); ++i) out << " ---: |";
  out << "\n";
  for (const ConfigKey& key : config_keys()) {
    out << "| `" << key.name << "` | " << part_name(key.part) << " | " << key.accepts() << " | " << key.doc << " |";
    for (const auto& [p, s] : files) {
      const nlohmann::json file = default_config_json(s, p);
      const RunConfig c = run_config_from_json(file, s);
      const std::string value = key.optional() && !file.contains(key.name) ? "absent" : key.write(c).dump();
      out << " " << (key.applies_to(s) ? value : "—") << " |";
    }
    out << "\n";
  }
  return out.str();
}

// The text between two marker lines of a document ("" if they are missing).
std::string between(const std::string& doc, const std::string& begin, const std::string& end) {
  const auto b = doc.find(begin), e = doc.find(end);
  if (b == std::string::npos || e == std::string::npos || e < b) return "";
  const auto start = doc.find('\n', b) + 1;
  return doc.substr(start, e - start);
}

}  // namespace

TEST(DefaultConfigs, EveryScenarioHasAValidConfigWithExactlyItsKeys) {
  for (const std::string& scenario : env_names()) {
    SCOPED_TRACE(scenario);
    const RunConfig c = run_config_from_json(default_config_json(scenario), scenario);
    EXPECT_GT(c.steps, c.warmup_steps);
    EXPECT_LE(c.eval_every, c.steps);
  }
}

TEST(DefaultConfigs, TheKeyTableOfDocsAlgorithmsMdIsTheConfigKeysAndFiles) {
  const std::string documented =
      between(read_doc("algorithms.md"), "<!-- config keys: begin", "<!-- config keys: end -->");
  EXPECT_EQ(documented, key_table_markdown())
      << "docs/algorithms.md's key table is out of date; replace the lines between its config-keys markers with:\n"
      << key_table_markdown();
}

TEST(DefaultConfigs, EpsilonOfEachDrivingScenarioIsTheOneDocsScenariosMdExplains) {
  const std::string doc = read_doc("scenarios.md");
  for (const std::string scenario : {"lane-drop", "cut-in", "merge"}) {
    SCOPED_TRACE(scenario);
    const std::string row = "\n| " + scenario + " | ";
    const auto at = doc.find(row);
    ASSERT_NE(at, std::string::npos) << "docs/scenarios.md has no ε row for " << scenario;
    const double documented = std::stod(doc.substr(at + row.size()));
    EXPECT_DOUBLE_EQ(documented, default_config_json(scenario).at("epsilon").get<double>());
  }
}

TEST(DefaultConfigs, OverridesAreCheckedByKeyTypeAndValue) {
  nlohmann::json base = default_config_json("pendulum");
  EXPECT_THROW(apply_overrides(base, {{"nosuchkey", 1}}, "pendulum", "test"), std::invalid_argument);
  EXPECT_THROW(apply_overrides(base, {{"steps", 1.5}}, "pendulum", "test"), std::invalid_argument);
  EXPECT_THROW(apply_overrides(base, {{"steps", -1}}, "pendulum", "test"), std::invalid_argument);
  EXPECT_THROW(apply_overrides(base, {{"actor_hidden", {64, "x"}}}, "pendulum", "test"), std::invalid_argument);
  apply_overrides(base, {{"steps", 123}, {"actor_lr", 1}}, "pendulum", "test");  // an integer is a fine number
  EXPECT_EQ(run_config_from_json(base, "pendulum").steps, 123);
  nlohmann::json sets = nlohmann::json::object();
  parse_set_option("actor_hidden=[32,32]", sets);
  parse_set_option("epsilon=-0.2", sets);
  EXPECT_EQ(sets["actor_hidden"], nlohmann::json({32, 32}));
  EXPECT_DOUBLE_EQ(sets["epsilon"].get<double>(), -0.2);
  EXPECT_THROW(parse_set_option("=3", sets), std::invalid_argument);
  EXPECT_THROW(parse_set_option("steps", sets), std::invalid_argument);
  EXPECT_THROW(parse_set_option("epsilon=0.1", sets), std::invalid_argument) << "given twice";
  EXPECT_DOUBLE_EQ(sets["epsilon"].get<double>(), -0.2);
}

TEST(DefaultConfigs, MessagesNameTheKeyAndWhatItAccepts) {
  nlohmann::json base = default_config_json("pendulum");
  const auto message = [&](const nlohmann::json& overrides) {
    try {
      apply_overrides(base, overrides, "pendulum", "--set");
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message({{"gamma", 1}}), "--set: config key 'gamma' must be in [0, 1), got 1");
  EXPECT_EQ(message({{"batch_size", 1}}), "--set: config key 'batch_size' must be at least 2, got 1");
  EXPECT_EQ(message({{"steps", "many"}}), "--set: config key 'steps' expects an integer, got \"many\"");
  EXPECT_EQ(message({{"critic_hidden", {64, 0}}}), "--set: config key 'critic_hidden' entries must each be positive, got [64,0]");
  EXPECT_EQ(message({{"stepz", 3}}), "--set: unknown config key 'stepz'");
  // Integers at or beyond 2^63 are nlohmann's unsigned numbers; read as an int they wrapped to 0
  // and passed every range check (issue 46: traffic_warmup=9223372036854775808 ran with none).
  const nlohmann::json huge = nlohmann::json::parse("9223372036854775808");
  EXPECT_EQ(message({{"steps", huge}}),
            "--set: config key 'steps' expects an integer from -9223372036854775808 to 9223372036854775807, got 9223372036854775808");
  EXPECT_EQ(message({{"batch_size", nlohmann::json::parse("4294967296")}}),
            "--set: config key 'batch_size' expects an integer from -2147483648 to 2147483647, got 4294967296");
  EXPECT_EQ(message({{"critic_hidden", {64, huge}}}),
            "--set: config key 'critic_hidden' expects a list of integers from -2147483648 to 2147483647, got [64,9223372036854775808]");
}

// A key that only some scenarios have (the driving scenarios' traffic, say) is required there,
// refused elsewhere, and may not be overridden where it does not apply.
TEST(DefaultConfigs, AKeyOfSomeScenariosOnlyIsRequiredThereAndRefusedElsewhere) {
  std::vector<ConfigKey> keys = config_keys();
  ConfigKey only_merge = *find_config_key("steps");
  only_merge.name = "merge_only";
  only_merge.for_scenario = [](const std::string& s) { return s == "merge"; };
  only_merge.read = [](const nlohmann::json&, RunConfig&) {};  // no field of its own
  keys.push_back(only_merge);

  nlohmann::json pendulum = default_config_json("pendulum");
  EXPECT_NO_THROW(run_config_from_json(pendulum, "pendulum", keys));
  EXPECT_THROW(apply_overrides(pendulum, {{"merge_only", 5}}, "pendulum", "test", keys), std::invalid_argument);
  pendulum["merge_only"] = 5;
  EXPECT_THROW(run_config_from_json(pendulum, "pendulum", keys), std::invalid_argument);

  nlohmann::json merge = default_config_json("merge");
  EXPECT_THROW(run_config_from_json(merge, "merge", keys), std::invalid_argument);  // missing
  apply_overrides(merge, {{"merge_only", 5}}, "merge", "test", keys);
  EXPECT_NO_THROW(run_config_from_json(merge, "merge", keys));
}

// An optional key may be left out of a config and then holds its neutral value; a required one
// may not. Given, an optional key is read like any other.
TEST(DefaultConfigs, AnOptionalKeyMayBeLeftOutAndThenHoldsItsNeutralValue) {
  int knob = -1;  // the synthetic keys' field
  std::vector<ConfigKey> keys = config_keys();
  ConfigKey optional = *find_config_key("steps");
  optional.name = "knob";
  optional.read = [&knob](const nlohmann::json& v, RunConfig&) { knob = v.get<int>(); };
  optional.set_neutral = [&knob](RunConfig&) { knob = 0; };
  keys.push_back(optional);

  nlohmann::json config = default_config_json("pendulum");
  EXPECT_NO_THROW(run_config_from_json(config, "pendulum", keys));
  EXPECT_EQ(knob, 0);
  config["knob"] = 5;
  run_config_from_json(config, "pendulum", keys);
  EXPECT_EQ(knob, 5);

  keys.back().set_neutral = nullptr;  // the same key, required
  EXPECT_FALSE(keys.back().optional());
  config.erase("knob");
  EXPECT_THROW(run_config_from_json(config, "pendulum", keys), std::invalid_argument);
}

// The real optional keys: no config file has them, and a config resolved from a file without one
// does not have it either, so their arrival changed no config hash; given, they are checked.
TEST(DefaultConfigs, OptionalKeysLeftOutOfAFileStayOutOfTheResolvedConfig) {
  for (const char* name : {"bc_q_alpha", "return_horizon", "utd_ratio", "critic_ensemble", "critic_subset",
                           "policy_delay", "target_noise", "target_noise_clip", "init_temperature",
                           "target_entropy_per_dim"}) {
    SCOPED_TRACE(name);
    ASSERT_TRUE(find_config_key(name)->optional());
    for (const auto& [p, s] : config_files()) {
      ASSERT_FALSE(default_config_json(s, p).contains(name)) << p << " " << s;
      EXPECT_FALSE(resolve_config(s, p, nlohmann::json(), nlohmann::json()).contains(name)) << p << " " << s;
    }
  }
  const RunConfig neutral = run_config_from_json(default_config_json("merge"), "merge");
  EXPECT_EQ(neutral.agent.method.number(kBcQAlpha), 0.0f);    // off
  EXPECT_EQ(neutral.agent.method.integer(kReturnHorizon), 0);   // not given
  const nlohmann::json given = resolve_config("merge", "short", {{"bc_q_alpha", 2.5}}, {{"return_horizon", 20}});
  EXPECT_EQ(given["bc_q_alpha"], 2.5);
  EXPECT_EQ(given["return_horizon"], 20);
  EXPECT_EQ(run_config_from_json(given, "merge").agent.method.integer(kReturnHorizon), 20);
  EXPECT_THROW(resolve_config("merge", "short", {{"return_horizon", 0}}, nlohmann::json()), std::invalid_argument);
  EXPECT_THROW(resolve_config("merge", "short", {{"bc_q_alpha", -1}}, nlohmann::json()), std::invalid_argument);
}

// Scenario keys: a short file leaves them out and gets the scenario's built-in values; the flow
// files set the paper's scale; values are checked by key, by scenario and across keys.
TEST(ScenarioKeys, ShortFilesKeepTheBuiltInSettingsAndFlowFilesSetThePapersScale) {
  for (const std::string scenario : {"lane-drop", "cut-in", "merge"}) {
    SCOPED_TRACE(scenario);
    const RunConfig short_config = run_config_from_json(default_config_json(scenario), scenario);
    const ScenarioSettings built_in = default_scenario_settings(scenario);
    EXPECT_EQ(short_config.scenario.horizon, built_in.horizon);
    EXPECT_EQ(short_config.scenario.action_repeat, 5);
    EXPECT_EQ(short_config.scenario.reward, "short");
    const RunConfig flow = run_config_from_json(default_config_json(scenario, "flow"), scenario);
    EXPECT_EQ(flow.scenario.action_repeat, 1);  // 0.1 s decisions
    EXPECT_GE(flow.scenario.horizon, 1500);
    EXPECT_EQ(flow.scenario.reward, "flow");
    EXPECT_EQ(flow.scenario.network, "long");
    EXPECT_FLOAT_EQ(flow.agent.method.number(kEpsilon), -0.15f);  // the paper's ε, unchanged in every scenario
  }
  EXPECT_THROW(check_profile("flow", "pendulum"), std::invalid_argument);
  EXPECT_THROW(check_profile("tiny", "merge"), std::invalid_argument);
  EXPECT_NO_THROW(check_profile("flow", "merge"));
}

TEST(ScenarioKeys, BadValuesAreRefusedNamingTheKey) {
  const auto message = [](const std::string& scenario, const nlohmann::json& overrides) {
    try {
      resolve_config(scenario, "flow", overrides, nlohmann::json());
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message("merge", {{"reward", "fast"}}), "grid: config key 'reward' expects one of short, flow, got \"fast\"");
  EXPECT_EQ(message("merge", {{"obstacles", 3}}), "grid: config key 'obstacles' does not apply to scenario 'merge'");
  EXPECT_EQ(message("lane-drop", {{"ramp_inflow", 100}}),
            "grid: config key 'ramp_inflow' does not apply to scenario 'lane-drop'");
  EXPECT_EQ(message("merge", {{"action_repeat", 0}}), "grid: config key 'action_repeat' must be in [1, 50], got 0");
  EXPECT_EQ(message("cut-in", {{"obstacle_speed_min", 20.0}}),
            "config key obstacle_speed_max: must be at least obstacle_speed_min");
  EXPECT_EQ(message("pendulum", {{"horizon", 100}}), "scenario 'pendulum' has no 'flow' profile");
  EXPECT_EQ(message("merge", {{"horizon", 100}}), "no error");
}


// An algorithm's recipe fills its own keys where the config leaves them out; a key the config
// gives wins; and an algorithm never sees the optional keys it does not list, so what a shared
// config sets for rlpd-sac or td3-bc cannot change the paper's five.
TEST(AlgorithmConfig, TheRecipeFillsOwnKeysAndOtherAlgorithmsKeysAreDropped) {
  const nlohmann::json plain = default_config_json("pendulum");
  const AgentConfig sac = check_config_fits("rlpd-sac", plain, "pendulum").agent;
  EXPECT_EQ(sac.method.integer(kUtdRatio), 20);
  EXPECT_EQ(sac.method.integer(kCriticEnsemble), 10);
  EXPECT_EQ(sac.method.integer(kCriticSubset), 2);
  EXPECT_EQ(sac.method.number(kInitTemperature), 1.0f);
  EXPECT_EQ(sac.method.number(kTargetEntropyPerDim), -0.5f);
  EXPECT_EQ(sac.method.integer(kPolicyDelay), 1);  // td3-bc's key: neutral
  EXPECT_EQ(sac.method.number(kTemperatureLr), 3e-4f);  // rlpd's temp_lr, not the actor's rate
  EXPECT_TRUE(sac.critic_layer_norm);
  EXPECT_EQ(sac.init, WeightInit::kXavier);
  const AgentConfig td3 = check_config_fits("td3-bc", plain, "pendulum").agent;
  EXPECT_EQ(td3.method.integer(kCriticEnsemble), 2);
  EXPECT_EQ(td3.method.integer(kCriticSubset), 2);
  EXPECT_EQ(td3.method.integer(kPolicyDelay), 2);
  EXPECT_EQ(td3.method.number(kTargetNoise), 0.2f);
  EXPECT_EQ(td3.method.number(kTargetNoiseClip), 0.5f);
  EXPECT_EQ(td3.method.number(kBcQAlpha), 2.5f);
  EXPECT_EQ(td3.method.integer(kUtdRatio), 1);
  EXPECT_FALSE(td3.critic_layer_norm);  // TD3_BC's critics have no LayerNorm
  EXPECT_EQ(td3.init, WeightInit::kPytorch);
  for (const char* algo : {"ddpg", "rlpd", "col-prior", "col-all", "rapid-rl"}) {
    const AgentConfig a = check_config_fits(algo, plain, "pendulum").agent;
    EXPECT_TRUE(a.critic_layer_norm) << algo;  // the paper's LayerNorm critic
    EXPECT_EQ(a.init, WeightInit::kDdpg) << algo;
  }
  // The switches are shared keys: a config may turn them for any algorithm, and wins over a recipe.
  nlohmann::json turned = plain;
  turned["critic_layer_norm"] = false;
  turned["init"] = "xavier";
  EXPECT_FALSE(check_config_fits("rapid-rl", turned, "pendulum").agent.critic_layer_norm);
  EXPECT_EQ(check_config_fits("td3-bc", turned, "pendulum").agent.init, WeightInit::kXavier);
  const auto refused = [&](const char* key, const nlohmann::json& value) {
    nlohmann::json c = plain;
    c[key] = value;
    try {
      check_config_fits("rlpd-sac", c, "pendulum");
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(refused("init", "he"), "config key 'init' expects one of ddpg, xavier, pytorch, got \"he\"");
  EXPECT_EQ(refused("critic_layer_norm", 1), "config key 'critic_layer_norm' expects true or false, got 1");
  EXPECT_EQ(refused("temperature_lr", 0), "config key 'temperature_lr' must be positive, got 0");

  nlohmann::json shared = plain;
  shared["critic_ensemble"] = 4;
  shared["utd_ratio"] = 3;
  shared["bc_q_alpha"] = 1.5;
  EXPECT_EQ(check_config_fits("rlpd-sac", shared, "pendulum").agent.method.integer(kCriticEnsemble), 4);
  EXPECT_EQ(check_config_fits("rlpd-sac", shared, "pendulum").agent.method.integer(kUtdRatio), 3);
  EXPECT_EQ(check_config_fits("td3-bc", shared, "pendulum").agent.method.number(kBcQAlpha), 1.5f);
  EXPECT_EQ(check_config_fits("td3-bc", shared, "pendulum").agent.method.integer(kUtdRatio), 1);
  for (const char* algo : {"ddpg", "rlpd", "col-all", "rapid-rl"}) {
    const AgentConfig a = check_config_fits(algo, shared, "pendulum").agent;
    EXPECT_EQ(a.method.integer(kCriticEnsemble), 1) << algo;
    EXPECT_EQ(a.method.integer(kUtdRatio), 1) << algo;
    EXPECT_EQ(a.method.number(kBcQAlpha), find_algorithm(algo).reads("bc_q_alpha") ? 1.5f : 0.0f) << algo;
  }
  // The recipe's keys are not part of the job's config: with_recipe adds them.
  EXPECT_FALSE(plain.contains("utd_ratio"));
  EXPECT_EQ(with_recipe(plain, "rlpd-sac")["utd_ratio"], 20);
  EXPECT_FALSE(with_recipe(shared, "ddpg").contains("critic_ensemble"));

  nlohmann::json bad = plain;
  bad["critic_subset"] = 3;
  bad["critic_ensemble"] = 2;
  try {
    check_config_fits("rlpd-sac", bad, "pendulum");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "algorithm 'rlpd-sac': config key 'critic_subset' must be 1 to critic_ensemble (2), got 3");
  }
  EXPECT_NO_THROW(check_config_fits("ddpg", bad, "pendulum"));  // not its keys
}
