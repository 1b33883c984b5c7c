// Resolving a run's config (RunConfig, config_keys.hpp): the chosen profile's keys that its
// scenarios share (experiments/configs/<profile>/shared.json), the scenario's own keys for that
// profile (its descriptor's "profiles" entry), then a grid's overrides, then `rapid run --set
// key=value`, each checked key by key against the key table. The resolved config is recorded in
// the run record and hashed.
#pragma once

#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "envs/env.hpp"
#include "experiments/run/config_keys.hpp"

namespace rapid {

// The folder with one subfolder of per-scenario config files per profile; RAPID_CONFIG_DIR
// overrides the built-in path.
std::string config_dir();

// The profiles: "short" (the scenarios as first built, the default) and "flow" (the paper's scale).
const std::vector<std::string>& config_profiles();
inline constexpr const char* kDefaultProfile = "short";

// Throws std::invalid_argument naming `scenario` if it is no scenario (check_scenario_name), or
// naming `profile` unless it is a profile with a file for `scenario`.
void check_profile(const std::string& profile, const std::string& scenario);

// One layer of a config: where its values come from (what an error or `rapid run --print-config`
// names) and the keys it sets.
struct ConfigLayer {
  std::string origin;
  nlohmann::json values;  // an object
};

// The layers of `scenario`'s config in `profile`, lowest first. A driving scenario, built-in or a
// file: the profile's shared keys (experiments/configs/<profile>/shared.json; a scenario file takes
// only its agent and schedule keys and writes its descriptor's settings above them), then the
// descriptor's "profiles" entry, checked here. The pendulum: its own file,
// experiments/configs/<profile>/pendulum.json. A config file missing or not a JSON object throws
// std::runtime_error.
std::vector<ConfigLayer> default_config_layers(const std::string& scenario, const std::string& profile);

// Those layers merged: the config of `scenario` in `profile` before any override.
nlohmann::json default_config_json(const std::string& scenario, const std::string& profile = kDefaultProfile);

// The agent and schedule keys of the profile's shared file: what a scenario file's run takes from
// the profile (its own keys may override them).
nlohmann::json shared_profile_config(const std::string& profile);

// Applies `overrides` (an object) onto `config`, a config of `scenario`: each key must be a config
// key of that scenario with a valid value. Throws std::invalid_argument "ORIGIN: …" naming the key.
void apply_overrides(nlohmann::json& config, const nlohmann::json& overrides, const std::string& scenario,
                     const std::string& origin, const std::vector<ConfigKey>& keys = config_keys());

// `layers` merged into one config of `scenario`: the first as it is, each later one applied with
// apply_overrides (its origin names it in an error). `origin`, when given, gets each key's layer.
nlohmann::json merge_layers(const std::vector<ConfigLayer>& layers, const std::string& scenario,
                            std::map<std::string, std::string>* origin = nullptr);

// Parses "key=value" (value as JSON, else as a plain string) into `overrides`. Throws
// std::invalid_argument for a malformed assignment or a key `overrides` already holds.
void parse_set_option(const std::string& assignment, nlohmann::json& overrides);

// A config resolved and parsed: `json` as a record holds it and its hash covers it, `run` its typed
// value. (A job's config, with its algorithm's recipe and each key's origin: job.hpp's ResolvedConfig.)
struct ParsedConfig {
  nlohmann::json json;
  RunConfig run;
};

// The config of `scenario` in `profile` with `overrides` (layers of config keys, lowest first) on
// top, merged as `rapid run` merges and parsed once. Throws std::invalid_argument naming the
// offending key (in the words of its layer's origin), the unknown scenario or the missing profile.
ParsedConfig resolve_run_config(const std::string& scenario, const std::string& profile,
                                  const std::vector<ConfigLayer>& overrides);

// The config of a cell: the scenario's file in `profile`, then the grid's overrides (if
// `grid_overrides` is an object), then `--set` overrides, validated as a whole. Throws
// std::invalid_argument naming the offending key.
nlohmann::json resolve_config(const std::string& scenario, const std::string& profile,
                              const nlohmann::json& grid_overrides, const nlohmann::json& set_overrides);

// Converts a config of `scenario`: it must have every key of that scenario (scenario keys and
// optional keys may be left out) and no other, each with a valid value. Throws
// std::invalid_argument naming the key.
RunConfig run_config_from_json(const nlohmann::json& j, const std::string& scenario,
                               const std::vector<ConfigKey>& keys = config_keys());

// How many configs this process has parsed with run_config_from_json: a test's way to see that a
// run resolves its config once.
long run_config_parses();

// The environment a run of `scenario` with `config` trains and evaluates in.
std::unique_ptr<Env> make_run_env(const std::string& scenario, const RunConfig& config);

}  // namespace rapid
