// The Gymnasium ids and specs of the harness's environments (docs/python.md §Gymnasium): the one
// statement of them, read by the Python module's registrations and by `rapid dataset export`'s
// Minari metadata, whose env_spec is what Minari's recover_environment() hands to gymnasium.make.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace rapid {

inline constexpr const char* kGymnasiumNamespace = "rapid";
// `rapid_harness.Env`: importing the module registers the ids and makes the class.
inline constexpr const char* kGymnasiumEntryPoint = "rapid_harness:Env";

// rapid/<name>-<profile>-v0, for a scenario's name (a built-in's, or the name a scenario file's
// descriptor gives itself). Throws std::invalid_argument for a name Gymnasium's ids cannot hold.
std::string gymnasium_env_id(const std::string& scenario_name, const std::string& profile);

// Gymnasium's EnvSpec, as EnvSpec.to_json() writes it, of `scenario` (a built-in name or a
// scenario file's path) in `profile` with `config` (config keys on top of the profile's; an empty
// object: none): gymnasium.make of it builds rapid_harness.Env(scenario, profile, config). The
// environment truncates itself at its horizon, so max_episode_steps is null.
nlohmann::json gymnasium_env_spec(const std::string& scenario, const std::string& profile,
                                  const nlohmann::json& config = nlohmann::json::object());

// The Minari dataset id of a prior dataset: rapid/<name>-<profile>/<dataset>-v0, '+' spelled '-'
// (Minari's ids hold letters, digits, '-' and '_'): rapid/merge-flow/final-medium-v0.
std::string minari_dataset_id(const std::string& scenario_name, const std::string& profile, const std::string& dataset);

}  // namespace rapid
