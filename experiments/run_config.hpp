// The fully resolved configuration of one training job: the agent's hyper-parameters plus the
// training schedule. Defaults live in one JSON file per scenario (experiments/configs/), a grid
// may override keys, and `rapid run --set key=value` overrides last. Every key must be known and
// of the default's type; the resolved config is recorded in the run record and hashed.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "algos/agent_config.hpp"
#include "envs/env.hpp"
#include <memory>
#include <optional>

namespace rapid {

struct RunConfig {
  AgentConfig agent;
  long steps = 20000;          // environment decisions of training
  long warmup_steps = 1000;    // uniform-random actions and no updates before this step
  long eval_every = 2000;      // evaluate at the first episode boundary after each multiple
  int eval_episodes = 5;       // deterministic policy, fixed evaluation seeds
  int last_k = 3;              // final performance = mean of the last K evaluations
  long bc_log_every = 500;     // BC-loss curve resolution (mean over the window's updates)
  long buffer_capacity = 1000000;
  std::optional<ScenarioSettings> scenario;  // driving scenarios whose config sets scenario keys
};

// The folder with the per-scenario default files; RAPID_CONFIG_DIR overrides the built-in path.
std::string config_dir();

// The defaults of `scenario` (throws std::runtime_error if its file is missing or malformed).
nlohmann::json default_config_json(const std::string& scenario);

// Applies `overrides` (an object) onto `base`: every key must exist in `base` with the same JSON
// type (integers where integers are expected). Throws std::invalid_argument naming the key.
void apply_overrides(nlohmann::json& base, const nlohmann::json& overrides, const std::string& origin);

// Parses "key=value" (value as JSON, else as a plain string) into `overrides`.
void parse_set_option(const std::string& assignment, nlohmann::json& overrides);

// Converts a validated config object; throws std::invalid_argument naming a bad value.
RunConfig run_config_from_json(const nlohmann::json& j);

// The environment a run of `scenario` trains in, with the config's scenario settings.
std::unique_ptr<Env> make_run_env(const std::string& scenario, const RunConfig& config);

}  // namespace rapid
