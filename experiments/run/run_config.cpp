#include "experiments/run/run_config.hpp"

#include <cstdlib>
#include <stdexcept>

#include "experiments/run/json_input.hpp"

namespace rapid {

std::string config_dir() {
  if (const char* dir = std::getenv("RAPID_CONFIG_DIR"); dir && *dir) return dir;
  return RAPID_DEFAULT_CONFIG_DIR;
}

nlohmann::json default_config_json(const std::string& scenario) {
  const std::string path = config_dir() + "/" + scenario + ".json";
  nlohmann::json j;
  try {
    j = read_json_input(path);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error("config file " + path + ": " + e.what());
  }
  if (!j.is_object()) throw std::runtime_error("config file " + path + ": not a JSON object");
  return j;
}

namespace {

// The row of `name`, which must be a key of `scenario`.
const ConfigKey& key_of(const std::string& name, const std::string& scenario, const std::vector<ConfigKey>& keys) {
  const ConfigKey* key = find_config_key(name, keys);
  if (!key) throw std::invalid_argument("unknown config key '" + name + "'");
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
      key_of(name, scenario, keys).read(value, scratch);  // checks the value where it is given
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(origin + ": " + e.what());
    }
    config[name] = value;
  }
}

void parse_set_option(const std::string& assignment, nlohmann::json& overrides) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throw std::invalid_argument("--set: expected key=value, got '" + assignment + "'");
  const std::string key = assignment.substr(0, eq), text = assignment.substr(eq + 1);
  nlohmann::json value = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (value.is_discarded()) value = text;
  overrides[key] = value;
}

nlohmann::json resolve_config(const std::string& scenario, const nlohmann::json& grid_overrides,
                              const nlohmann::json& set_overrides) {
  nlohmann::json config = default_config_json(scenario);
  if (grid_overrides.is_object()) apply_overrides(config, grid_overrides, scenario, "grid");
  if (set_overrides.is_object()) apply_overrides(config, set_overrides, scenario, "--set");
  run_config_from_json(config, scenario);  // validates the whole
  return config;
}

RunConfig run_config_from_json(const nlohmann::json& j, const std::string& scenario,
                               const std::vector<ConfigKey>& keys) {
  if (!j.is_object()) throw std::invalid_argument("config must be a JSON object");
  for (const ConfigKey& key : keys)
    if (key.applies_to(scenario) && !j.contains(key.name))
      throw std::invalid_argument("config is missing key '" + key.name + "'");
  RunConfig config;
  for (const auto& [name, value] : j.items()) key_of(name, scenario, keys).read(value, config);
  return config;
}

}  // namespace rapid
