#include "experiments/run_config.hpp"

#include <cstdlib>
#include <fstream>
#include <stdexcept>

namespace rapid {

std::string config_dir() {
  if (const char* dir = std::getenv("RAPID_CONFIG_DIR"); dir && *dir) return dir;
  return RAPID_DEFAULT_CONFIG_DIR;
}

nlohmann::json default_config_json(const std::string& scenario) {
  const std::string path = config_dir() + "/" + scenario + ".json";
  std::ifstream in(path);
  if (!in) throw std::runtime_error("missing config file " + path);
  try {
    nlohmann::json j = nlohmann::json::parse(in);
    if (!j.is_object()) throw std::runtime_error("not a JSON object");
    return j;
  } catch (const std::exception& e) {
    throw std::runtime_error("config file " + path + ": " + e.what());
  }
}

namespace {
bool same_kind(const nlohmann::json& want, const nlohmann::json& got) {
  if (want.is_number_integer()) return got.is_number_integer();
  if (want.is_number()) return got.is_number();
  if (want.is_array()) {
    if (!got.is_array()) return false;
    for (const auto& e : got)
      if (!want.empty() && !same_kind(want.front(), e)) return false;
    return true;
  }
  return want.type() == got.type();
}
}  // namespace

void apply_overrides(nlohmann::json& base, const nlohmann::json& overrides, const std::string& origin) {
  if (!overrides.is_object()) throw std::invalid_argument(origin + ": overrides must be an object");
  for (const auto& [key, value] : overrides.items()) {
    if (!base.contains(key)) throw std::invalid_argument(origin + ": unknown config key '" + key + "'");
    if (!same_kind(base[key], value))
      throw std::invalid_argument(origin + ": config key '" + key + "' expects " +
                                  std::string(base[key].type_name()) + " like " + base[key].dump() +
                                  ", got " + value.dump());
    base[key] = value;
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

namespace {
template <typename T>
T positive(const nlohmann::json& j, const char* key) {
  const T v = j.at(key).get<T>();
  if (!(v > 0)) throw std::invalid_argument(std::string("config key '") + key + "' must be positive, got " + j.at(key).dump());
  return v;
}
template <typename T>
T non_negative(const nlohmann::json& j, const char* key) {
  const T v = j.at(key).get<T>();
  if (!(v >= 0)) throw std::invalid_argument(std::string("config key '") + key + "' must be ≥ 0, got " + j.at(key).dump());
  return v;
}
std::vector<int> widths(const nlohmann::json& j, const char* key) {
  std::vector<int> w = j.at(key).get<std::vector<int>>();
  if (w.empty()) throw std::invalid_argument(std::string("config key '") + key + "' needs at least one layer");
  for (int x : w)
    if (x <= 0) throw std::invalid_argument(std::string("config key '") + key + "' has a non-positive width");
  return w;
}
}  // namespace

RunConfig run_config_from_json(const nlohmann::json& j) {
  static const char* const kKeys[] = {"actor_hidden", "critic_hidden", "actor_lr", "critic_lr", "gamma", "tau",
                                      "batch_size", "noise_std", "lambda_bc", "epsilon", "steps", "warmup_steps",
                                      "eval_every", "eval_episodes", "last_k", "bc_log_every", "buffer_capacity"};
  for (const char* k : kKeys)
    if (!j.contains(k)) throw std::invalid_argument(std::string("config is missing key '") + k + "'");
  static const char* const kScenarioKeys[] = {"network", "action_repeat", "horizon", "lane_change_interval",
                                              "traffic_warmup", "max_depart_delay", "desired_speed", "reward", "inflow", "ramp_inflow",
                                              "obstacles", "obstacle_speed_min", "obstacle_speed_max"};
  for (const auto& [key, v] : j.items()) {
    bool known = false;
    for (const char* k : kKeys) known = known || key == k;
    for (const char* k : kScenarioKeys) known = known || key == k;
    if (!known) throw std::invalid_argument("unknown config key '" + key + "'");
  }
  try {
    RunConfig c;
    c.agent.actor_hidden = widths(j, "actor_hidden");
    c.agent.critic_hidden = widths(j, "critic_hidden");
    c.agent.actor_lr = positive<float>(j, "actor_lr");
    c.agent.critic_lr = positive<float>(j, "critic_lr");
    c.agent.gamma = non_negative<float>(j, "gamma");
    if (c.agent.gamma >= 1.0f) throw std::invalid_argument("config key 'gamma' must be below 1");
    c.agent.tau = positive<float>(j, "tau");
    if (c.agent.tau > 1.0f) throw std::invalid_argument("config key 'tau' must be at most 1");
    c.agent.batch_size = positive<int>(j, "batch_size");
    if (c.agent.batch_size < 2) throw std::invalid_argument("config key 'batch_size' must be at least 2");
    c.agent.noise_std = non_negative<float>(j, "noise_std");
    c.agent.lambda_bc = non_negative<float>(j, "lambda_bc");
    c.agent.epsilon = j.at("epsilon").get<float>();
    c.steps = positive<long>(j, "steps");
    c.warmup_steps = non_negative<long>(j, "warmup_steps");
    c.eval_every = positive<long>(j, "eval_every");
    c.eval_episodes = positive<int>(j, "eval_episodes");
    c.last_k = positive<int>(j, "last_k");
    c.bc_log_every = positive<long>(j, "bc_log_every");
    c.buffer_capacity = positive<long>(j, "buffer_capacity");
    if (j.contains("horizon")) {
      ScenarioSettings s;
      s.network = j.at("network").get<std::string>();
      s.action_repeat = j.at("action_repeat").get<int>();
      s.horizon = j.at("horizon").get<int>();
      s.lane_change_interval = j.at("lane_change_interval").get<int>();
      s.traffic_warmup = j.at("traffic_warmup").get<int>();
      s.desired_speed = j.at("desired_speed").get<double>();
      s.max_depart_delay = j.at("max_depart_delay").get<double>();
      s.reward = j.at("reward").get<std::string>();
      s.inflow = j.at("inflow").get<double>();
      s.ramp_inflow = j.value("ramp_inflow", 0.0);
      s.obstacles = j.value("obstacles", 0);
      s.obstacle_speed_min = j.value("obstacle_speed_min", 0.0);
      s.obstacle_speed_max = j.value("obstacle_speed_max", 0.0);
      c.scenario = s;
    }
    return c;
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument(std::string("config has a value of the wrong type: ") + e.what());
  }
}

}  // namespace rapid

namespace rapid {
std::unique_ptr<Env> make_run_env(const std::string& scenario, const RunConfig& config) {
  return config.scenario ? make_env(scenario, *config.scenario) : make_env(scenario);
}
}  // namespace rapid
