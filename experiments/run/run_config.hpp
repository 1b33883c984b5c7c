// The fully resolved configuration of one training job: the agent's hyper-parameters plus the
// training schedule. Its keys are the rows of config_keys.hpp. Values live in one JSON file per
// scenario (experiments/configs/<scenario>.json); a grid may override keys, and `rapid run --set
// key=value` overrides last. The resolved config is recorded in the run record and hashed.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "algos/agent_config.hpp"
#include "experiments/run/config_keys.hpp"

namespace rapid {

// No defaults: every field comes from the scenario's config file through its config key.
struct RunConfig {
  AgentConfig agent;
  long steps{};
  long warmup_steps{};
  long eval_every{};
  int eval_episodes{};
  int last_k{};
  long bc_log_every{};
  long buffer_capacity{};
};

// The folder with the per-scenario config files; RAPID_CONFIG_DIR overrides the built-in path.
std::string config_dir();

// The config file of `scenario` as it is (throws std::runtime_error if it is missing or not a
// JSON object; its keys are checked when it is parsed).
nlohmann::json default_config_json(const std::string& scenario);

// Applies `overrides` (an object) onto `config`, a config of `scenario`: each key must be a config
// key of that scenario with a valid value. Throws std::invalid_argument "ORIGIN: …" naming the key.
void apply_overrides(nlohmann::json& config, const nlohmann::json& overrides, const std::string& scenario,
                     const std::string& origin, const std::vector<ConfigKey>& keys = config_keys());

// Parses "key=value" (value as JSON, else as a plain string) into `overrides`.
void parse_set_option(const std::string& assignment, nlohmann::json& overrides);

// Converts a config of `scenario`: it must have every key of that scenario and no other, each
// with a valid value. Throws std::invalid_argument naming the key.
RunConfig run_config_from_json(const nlohmann::json& j, const std::string& scenario,
                               const std::vector<ConfigKey>& keys = config_keys());

}  // namespace rapid
