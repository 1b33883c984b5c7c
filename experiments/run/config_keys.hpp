// A run's config, RunConfig, and its keys, one row each: the one place that says which keys
// exist, which part of a run each configures, the field it fills, the values it accepts and what
// it means. Parsing, validation, grid overrides and `--set` (run_config.hpp) read this table, and
// the key table of docs/algorithms.md is generated from it (tests/test_configs.cpp fails when they
// differ). The values runs use live in the profile's shared file, experiments/configs/<profile>/
// shared.json, and in each scenario's descriptor (its "profiles" entry).
#pragma once

#include <functional>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "algos/agent_config.hpp"
#include "core/bounds.hpp"
#include "envs/scenario_settings.hpp"

namespace rapid {

// The fully resolved configuration of one training job: the agent's hyper-parameters plus the
// training schedule. No defaults: every field comes from the scenario's config file through its
// key below.
struct RunConfig {
  AgentConfig agent;
  long steps{};
  long warmup_steps{};
  long eval_every{};
  int eval_episodes{};
  int last_k{};
  int final_eval_episodes{};  // 0: no final evaluation (the final return is the last K evaluations' mean)
  long bc_log_every{};
  long buffer_capacity{};
  // A driving scenario's knobs. Scenario keys are the one kind a config file may leave out: a
  // missing one keeps the scenario's built-in `short` value (envs/scenario_settings.cpp), so the
  // short profile's files and config hashes predate the keys.
  ScenarioSettings scenario;
};

// The part of a run a key configures; it follows from the struct that holds the key's field.
enum class ConfigPart {
  kAgent,     // the learner: networks, optimiser, losses (AgentConfig, algos/)
  kSchedule,  // the training schedule: budget, warm-up, evaluation, logging (RunConfig)
  kScenario,  // the simulated scenario: ScenarioSettings, owned by envs/ (optional keys)
};

// "agent", "schedule", "scenario".
const char* part_name(ConfigPart part);

struct ConfigKey {
  std::string name;
  ConfigPart part = ConfigPart::kSchedule;
  std::string type;  // "integer", "number", "list of integers" or "one of a, b"
  Bounds bounds;     // the numbers it accepts (for a list: each entry)
  std::string doc;   // one line: what the key means
  // The scenarios that have the key; null: every scenario. A key of one kind of scenario only
  // (a driving scenario's traffic, say) is missing from the others' configs and refused there.
  bool (*for_scenario)(const std::string& scenario) = nullptr;
  // Checks the value's type and bounds and stores it in the key's field of `config`. Throws
  // std::invalid_argument("config key 'K' …") saying what is wrong.
  std::function<void(const nlohmann::json& value, RunConfig& config)> read;
  // The key's value in `config`, as JSON.
  std::function<nlohmann::json(const RunConfig& config)> write;
  // Null for a required key. For an optional one, a config may leave the key out, and then this
  // puts the key's neutral value in its field: one that changes nothing (bc_q_alpha 0: off) or
  // says the key was not given (return_horizon 0, outside its bounds: the algorithm that needs it
  // refuses to run). A key left out stays out of the resolved config, so adding an optional key
  // changes no existing config hash. (Scenario keys may be left out too, and then hold the
  // scenario's built-in value: RunConfig::scenario.)
  std::function<void(RunConfig& config)> set_neutral;
  // Null for most keys. For a key whose value names something the scenario's descriptor defines
  // (its networks, its reward variants): throws std::invalid_argument("config key 'K' …") if the
  // value names nothing `scenario` has.
  std::function<void(const nlohmann::json& value, const std::string& scenario)> check_for_scenario;

  bool applies_to(const std::string& scenario) const { return for_scenario == nullptr || for_scenario(scenario); }
  bool optional() const { return static_cast<bool>(set_neutral); }
  // The type and bounds as one phrase: "integer, positive", "list of integers, each positive".
  std::string accepts() const;
};

// Every key of a run config, in the order the docs list them.
const std::vector<ConfigKey>& config_keys();

// The row of `name` in `keys`; nullptr when there is none.
const ConfigKey* find_config_key(const std::string& name, const std::vector<ConfigKey>& keys = config_keys());

}  // namespace rapid
