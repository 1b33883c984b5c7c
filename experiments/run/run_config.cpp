#include "experiments/run/run_config.hpp"

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>

#include "core/printable.hpp"
#include "envs/scenario_descriptor.hpp"
#include "core/json_input.hpp"

namespace rapid {

std::string config_dir() {
  if (const char* dir = std::getenv("RAPID_CONFIG_DIR"); dir && *dir) return dir;
  return RAPID_DEFAULT_CONFIG_DIR;
}

const std::vector<std::string>& config_profiles() {
  static const std::vector<std::string> names = {"short", "flow"};
  return names;
}

namespace {
// A scenario file, named by its path or by the name a grid gave it.
bool is_scenario_from_file(const std::string& scenario) {
  return is_driving_scenario(scenario) && !is_builtin_scenario(scenario);
}

// A config file of the profile's folder, which must be a JSON object.
nlohmann::json read_config_file(const std::string& path) {
  nlohmann::json j;
  try {
    j = read_json_input(path);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error("config file " + path + ": " + e.what());
  }
  if (!j.is_object()) throw std::runtime_error("config file " + path + ": not a JSON object");
  return j;
}

std::string shared_config_path(const std::string& profile) { return config_dir() + "/" + profile + "/shared.json"; }
// The config of a scenario that is no driving scenario (the pendulum): a file of its own.
std::string own_config_path(const std::string& scenario, const std::string& profile) {
  return config_dir() + "/" + profile + "/" + scenario + ".json";
}
}  // namespace

void check_profile(const std::string& profile, const std::string& scenario) {
  check_scenario_name(scenario);
  const auto& names = config_profiles();
  if (std::find(names.begin(), names.end(), profile) == names.end())
    throw std::invalid_argument("unknown profile '" + profile + "' (profiles: " + comma_joined(names) + ")");
  if (!is_driving_scenario(scenario)) {
    if (!std::filesystem::exists(own_config_path(scenario, profile)))
      throw std::invalid_argument("scenario '" + scenario + "' has no '" + profile + "' profile");
    return;
  }
  if (!scenario_descriptor(scenario)->profiles.contains(profile)) {
    if (is_scenario_from_file(scenario))
      throw std::invalid_argument("scenario file " + scenario + " has no '" + profile + "' profile (profiles." + profile +
                                  " is missing)");
    throw std::invalid_argument("scenario '" + scenario + "' has no '" + profile + "' profile");
  }
}

nlohmann::json shared_profile_config(const std::string& profile) {
  nlohmann::json shared = read_config_file(shared_config_path(profile));
  for (auto it = shared.begin(); it != shared.end();) {
    const ConfigKey* k = find_config_key(it.key());
    it = k != nullptr && k->part != ConfigPart::kScenario ? std::next(it) : shared.erase(it);
  }
  return shared;
}

namespace {
// A driving scenario's layers in `profile`: the profile's shared keys (experiments/configs/<profile>/
// shared.json), then the descriptor's keys for that profile (checked here, as a whole). A scenario
// file's layers put its descriptor's settings, written out as scenario keys, between the two and
// take only the shared agent and schedule keys: its road is its own. A built-in scenario's settings
// stay the descriptor's defaults, unwritten (run_config_from_json starts from them), and the
// shared file's scenario keys apply to it: so its resolved config, and every record's hash, is what
// it was when each built-in had a config file per profile.
std::vector<ConfigLayer> driving_scenario_layers(const std::string& scenario, const std::string& profile) {
  check_profile(profile, scenario);
  const auto descriptor = scenario_descriptor(scenario);
  const bool from_file = is_scenario_from_file(scenario);
  const std::string path = shared_config_path(profile);
  std::vector<ConfigLayer> layers;
  if (from_file) {
    layers.push_back({"profile " + profile + " (" + path + ", its agent and schedule keys)", shared_profile_config(profile)});
    ConfigLayer settings{"scenario file " + scenario, nlohmann::json::object()};
    RunConfig with_defaults;
    with_defaults.scenario = descriptor->defaults;
    for (const ConfigKey& key : config_keys())
      if (key.part == ConfigPart::kScenario && key.applies_to(scenario))
        settings.values[key.name] = key.write(with_defaults);
    layers.push_back(std::move(settings));
  } else {
    layers.push_back({"profile " + profile + " (" + path + ")", read_config_file(path)});
  }
  const std::string own_origin = (from_file ? "scenario file " : "scenario ") + scenario + ": profiles." + profile;
  ConfigLayer own{own_origin, descriptor->profiles.at(profile)};
  nlohmann::json config = nlohmann::json::object();
  for (const ConfigLayer& layer : layers) config.update(layer.values);
  apply_overrides(config, own.values, scenario, own.origin);
  for (const ConfigKey& key : config_keys())
    if (!key.optional() && key.applies_to(scenario) && !config.contains(key.name) &&
        (from_file || key.part != ConfigPart::kScenario))
      throw std::invalid_argument(own.origin + ": must give '" + key.name + "' (the profile's scenarios differ in it)");
  layers.push_back(std::move(own));
  return layers;
}
}  // namespace

std::vector<ConfigLayer> default_config_layers(const std::string& scenario, const std::string& profile) {
  if (is_driving_scenario(scenario)) return driving_scenario_layers(scenario, profile);
  const std::string path = own_config_path(scenario, profile);
  return {{"config file " + path, read_config_file(path)}};
}

nlohmann::json default_config_json(const std::string& scenario, const std::string& profile) {
  nlohmann::json config = nlohmann::json::object();
  for (const ConfigLayer& layer : default_config_layers(scenario, profile)) config.update(layer.values);
  return config;
}

namespace {

// The row of `name`, which must be a key of `scenario`.
const ConfigKey& key_of(const std::string& name, const std::string& scenario, const std::vector<ConfigKey>& keys) {
  const ConfigKey* key = find_config_key(name, keys);
  if (!key) throw std::invalid_argument("unknown config key '" + printable(name) + "'");
  if (!key->applies_to(scenario))
    throw std::invalid_argument("config key '" + name + "' does not apply to scenario '" + scenario + "'");
  return *key;
}

}  // namespace

void apply_overrides(nlohmann::json& config, const nlohmann::json& overrides, const std::string& scenario,
                     const std::string& origin, const std::vector<ConfigKey>& keys) {
  if (!overrides.is_object()) throw std::invalid_argument(origin + ": overrides must be an object");
  for (const auto& [name, value] : overrides.items()) {
    try {
      RunConfig scratch;
      const ConfigKey& key = key_of(name, scenario, keys);
      key.read(value, scratch);  // checks the value where it is given
      if (key.check_for_scenario) key.check_for_scenario(value, scenario);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(origin + ": " + e.what());
    }
    config[name] = value;
  }
}

nlohmann::json merge_layers(const std::vector<ConfigLayer>& layers, const std::string& scenario,
                            std::map<std::string, std::string>* origin) {
  nlohmann::json config = nlohmann::json::object();
  for (std::size_t i = 0; i < layers.size(); ++i) {
    if (i == 0) config = layers[i].values;
    else apply_overrides(config, layers[i].values, scenario, layers[i].origin);
    if (origin)
      for (const auto& [key, value] : layers[i].values.items()) (*origin)[key] = layers[i].origin;
  }
  return config;
}

void parse_set_option(const std::string& assignment, nlohmann::json& overrides) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throw std::invalid_argument("--set: expected key=value, got '" + assignment + "'");
  const std::string key = assignment.substr(0, eq), text = assignment.substr(eq + 1);
  // Two values for one key are a mistake (a copied command line), not "the last one wins".
  if (overrides.contains(key)) throw std::invalid_argument("--set: key '" + key + "' is given twice");
  nlohmann::json value = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (value.is_discarded()) value = text;
  overrides[key] = value;
}

ParsedConfig resolve_run_config(const std::string& scenario, const std::string& profile,
                                  const std::vector<ConfigLayer>& overrides) {
  check_profile(profile, scenario);
  std::vector<ConfigLayer> layers = default_config_layers(scenario, profile);
  layers.insert(layers.end(), overrides.begin(), overrides.end());
  nlohmann::json config = merge_layers(layers, scenario);  // the merge `rapid run` makes
  RunConfig run = run_config_from_json(config, scenario);  // validates the whole
  return {std::move(config), std::move(run)};
}

nlohmann::json resolve_config(const std::string& scenario, const std::string& profile,
                              const nlohmann::json& grid_overrides, const nlohmann::json& set_overrides) {
  std::vector<ConfigLayer> overrides;
  if (grid_overrides.is_object()) overrides.push_back({"grid", grid_overrides});
  if (set_overrides.is_object()) overrides.push_back({"--set", set_overrides});
  return resolve_run_config(scenario, profile, overrides).json;
}

namespace {
std::atomic<long> parses{0};
}  // namespace

long run_config_parses() { return parses.load(); }

RunConfig run_config_from_json(const nlohmann::json& j, const std::string& scenario,
                               const std::vector<ConfigKey>& keys) {
  ++parses;
  if (!j.is_object()) throw std::invalid_argument("config must be a JSON object");
  for (const ConfigKey& key : keys)
    if (key.part != ConfigPart::kScenario && !key.optional() && key.applies_to(scenario) && !j.contains(key.name))
      throw std::invalid_argument("config is missing key '" + key.name + "'");
  RunConfig config;
  if (is_driving_scenario(scenario)) config.scenario = default_scenario_settings(scenario);
  for (const ConfigKey& key : keys)
    if (key.optional()) key.set_neutral(config);
  for (const auto& [name, value] : j.items()) key_of(name, scenario, keys).read(value, config);
  if (is_driving_scenario(scenario)) {
    try {
      validate_scenario_settings(scenario, config.scenario);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("config key ") + e.what());
    }
  }
  return config;
}

std::unique_ptr<Env> make_run_env(const std::string& scenario, const RunConfig& config) {
  return is_driving_scenario(scenario) ? make_env(scenario, config.scenario) : make_env(scenario);
}

}  // namespace rapid
