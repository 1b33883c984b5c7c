#include "experiments/run/gymnasium_spec.hpp"

#include <algorithm>
#include <regex>
#include <stdexcept>

#include "envs/scenario_descriptor.hpp"

namespace rapid {

namespace {

std::string scenario_name_of(const std::string& scenario) {
  return is_scenario_file(scenario) ? scenario_descriptor(scenario)->name : scenario;
}

}  // namespace

std::string gymnasium_env_id(const std::string& scenario_name, const std::string& profile) {
  // Gymnasium's env id pattern (gymnasium/envs/registration.py) without the namespace and version.
  static const std::regex name(R"([\w:.-]+)");
  if (!std::regex_match(scenario_name, name) || !std::regex_match(profile, name))
    throw std::invalid_argument("'" + scenario_name + "' in profile '" + profile + "' makes no Gymnasium id");
  return std::string(kGymnasiumNamespace) + "/" + scenario_name + "-" + profile + "-v0";
}

nlohmann::json gymnasium_env_spec(const std::string& scenario, const std::string& profile, const nlohmann::json& config) {
  nlohmann::json kwargs = {{"scenario", scenario}, {"profile", profile}};
  if (!config.empty()) kwargs["config"] = config;
  return {{"id", gymnasium_env_id(scenario_name_of(scenario), profile)},
          {"entry_point", kGymnasiumEntryPoint},
          {"reward_threshold", nullptr},
          {"nondeterministic", false},
          {"max_episode_steps", nullptr},
          {"order_enforce", true},
          {"disable_env_checker", false},
          {"kwargs", kwargs},
          {"additional_wrappers", nlohmann::json::array()},
          {"vector_entry_point", nullptr}};
}

std::string minari_dataset_id(const std::string& scenario_name, const std::string& profile, const std::string& dataset) {
  std::string name = dataset;
  std::replace(name.begin(), name.end(), '+', '-');
  return std::string(kGymnasiumNamespace) + "/" + scenario_name + "-" + profile + "/" + name + "-v0";
}

}  // namespace rapid
