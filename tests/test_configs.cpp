// The config key table (experiments/run/config_keys.cpp) against everything that must agree with it:
// every scenario's config file, the key table of docs/algorithms.md and the ε table of
// docs/scenarios.md; and overrides checked by key, type, value and scenario.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "envs/env.hpp"
#include "experiments/run/run_config.hpp"

using namespace rapid;

namespace {

std::string read_doc(const std::string& name) {
  std::ifstream in(std::string(RAPID_SOURCE_DIR) + "/docs/" + name);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// The key table as docs/algorithms.md must show it: one row per key, one value column per scenario.
std::string key_table_markdown() {
  std::ostringstream out;
  out << "| key | configures | accepts | meaning |";
  for (const std::string& s : env_names()) out << " " << s << " |";
  out << "\n| --- | --- | --- | --- |";
  for (std::size_t i = 0; i < env_names().size(); ++i) out << " ---: |";
  out << "\n";
  for (const ConfigKey& key : config_keys()) {
    out << "| `" << key.name << "` | " << part_name(key.part) << " | " << key.accepts() << " | " << key.doc << " |";
    for (const std::string& s : env_names()) out << " " << (key.applies_to(s) ? default_config_json(s).at(key.name).dump() : "—") << " |";
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
  for (const std::string& scenario : {"lane-drop", "cut-in", "merge"}) {
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
