#include "experiments/run/config_keys.hpp"

#include "envs/env.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <stdexcept>
#include <type_traits>

#include "algos/registry.hpp"
#include "core/json_input.hpp"
#include "core/printable.hpp"
#include "envs/scenario_descriptor.hpp"

namespace rapid {

namespace {

constexpr Bounds at_least(double x) { return {.lo = x}; }

[[noreturn]] void reject(const std::string& key, const std::string& problem) {
  throw std::invalid_argument("config key '" + key + "' " + problem);
}

// Whether `v` is a JSON integer that T holds (json_integer: never one wrapped from 2^63 or more).
template <typename T>
bool fits(const nlohmann::json& v) {
  const std::optional<long long> i = json_integer(v);
  return i && *i >= std::numeric_limits<T>::min() && *i <= std::numeric_limits<T>::max();
}

template <typename T>
std::string range_text() {
  return " from " + std::to_string(std::numeric_limits<T>::min()) + " to " + std::to_string(std::numeric_limits<T>::max());
}

// The JSON value in the type of the key's field, or a message naming that type.
template <typename T>
T typed(const std::string& key, const nlohmann::json& v) {
  if constexpr (std::is_same_v<T, bool>) {
    if (!v.is_boolean()) reject(key, "expects true or false, got " + json_excerpt(v));
  } else if constexpr (std::is_floating_point_v<T>) {
    if (!v.is_number()) reject(key, "expects a number, got " + json_excerpt(v));
    if (!std::isfinite(v.get<double>())) reject(key, "expects a finite number, got " + json_excerpt(v));
  } else if constexpr (std::is_integral_v<T>) {
    if (!v.is_number_integer()) reject(key, "expects an integer, got " + json_excerpt(v));
    if (!fits<T>(v)) reject(key, "expects an integer" + range_text<T>() + ", got " + json_excerpt(v));
  } else {
    static_assert(std::is_same_v<T, std::vector<int>>);
    if (!v.is_array()) reject(key, "expects a list of integers, got " + json_excerpt(v));
    for (const auto& e : v) {
      if (!e.is_number_integer()) reject(key, "expects a list of integers, got " + json_excerpt(v));
      if (!fits<int>(e)) reject(key, "expects a list of integers" + range_text<int>() + ", got " + json_excerpt(v));
    }
    if (v.empty()) reject(key, "needs at least one entry");
  }
  return v.get<T>();
}

template <typename T>
const char* type_name() {
  if constexpr (std::is_same_v<T, bool>) return "true or false";
  else if constexpr (std::is_floating_point_v<T>) return "number";
  else if constexpr (std::is_integral_v<T>) return "integer";
  else return "list of integers";
}

void check_bounds(const std::string& key, const Bounds& bounds, double x, const nlohmann::json& v) {
  if (!bounds.contains(x)) reject(key, "must be " + bounds.text() + ", got " + json_excerpt(v));
}

void check_bounds(const std::string& key, const Bounds& bounds, const std::vector<int>& xs, const nlohmann::json& v) {
  for (int x : xs)
    if (!bounds.contains(x)) reject(key, "entries must each be " + bounds.text() + ", got " + json_excerpt(v));
}

// The struct that holds a field decides the part the key configures.
template <typename Holder>
constexpr ConfigPart part_of() {
  if constexpr (std::is_same_v<Holder, AgentConfig>) return ConfigPart::kAgent;
  else if constexpr (std::is_same_v<Holder, ScenarioSettings>) return ConfigPart::kScenario;
  else {
    static_assert(std::is_same_v<Holder, RunConfig>);
    return ConfigPart::kSchedule;
  }
}

template <typename Holder, typename Config>
auto& holder(Config& config) {
  if constexpr (std::is_same_v<Holder, AgentConfig>) return config.agent;
  else if constexpr (std::is_same_v<Holder, ScenarioSettings>) return config.scenario;
  else return config;
}

bool driving_only(const std::string& scenario) { return is_driving_scenario(scenario); }
// Keys of roads with an on-ramp flow, and of roads with cut-in obstacles (their descriptors say).
bool merge_only(const std::string& scenario) { return driving_only(scenario) && scenario_descriptor(scenario)->has_ramp_inflow; }
bool cut_in_only(const std::string& scenario) {
  return driving_only(scenario) && scenario_descriptor(scenario)->hook == kCutInObstaclesHook;
}

// A row: the key's name, its field, the values it accepts and what it means.
template <typename T, typename Holder>
ConfigKey key(std::string name, T Holder::*field, Bounds bounds, std::string doc,
              bool (*for_scenario)(const std::string&) = nullptr) {
  ConfigKey k{name, part_of<Holder>(), type_name<T>(), bounds, std::move(doc), for_scenario, {}, {}, {}, {}};
  k.read = [name, field, bounds](const nlohmann::json& v, RunConfig& config) {
    const T x = typed<T>(name, v);
    if constexpr (!std::is_same_v<T, bool>) check_bounds(name, bounds, x, v);
    holder<Holder>(config).*field = x;
  };
  k.write = [field](const RunConfig& config) { return nlohmann::json(holder<Holder>(config).*field); };
  return k;
}

// A row a config may leave out; its field then holds `neutral` (ConfigKey::set_neutral).
template <typename T, typename Holder>
ConfigKey optional_key(std::string name, T Holder::*field, Bounds bounds, T neutral, std::string doc) {
  ConfigKey k = key(std::move(name), field, bounds, std::move(doc));
  k.set_neutral = [field, neutral](RunConfig& config) { holder<Holder>(config).*field = neutral; };
  return k;
}

// A row whose value names one of the things the scenario's descriptor defines (`names` of it: its
// networks, its reward variants beside the built-in ones).
ConfigKey descriptor_choice_key(std::string name, std::string ScenarioSettings::*field, std::string type,
                                std::string doc, std::vector<std::string> (*names)(const ScenarioDescriptor&)) {
  ConfigKey k{name, ConfigPart::kScenario, std::move(type), kAnyNumber, std::move(doc), driving_only, {}, {}, {}, {}};
  k.read = [name, field](const nlohmann::json& v, RunConfig& config) {
    if (!v.is_string() || v.get<std::string>().empty()) reject(name, "expects a name, got " + json_excerpt(v));
    config.scenario.*field = v.get<std::string>();
  };
  k.write = [field](const RunConfig& config) { return nlohmann::json(config.scenario.*field); };
  k.check_for_scenario = [name, names](const nlohmann::json& v, const std::string& scenario) {
    const std::vector<std::string> choices = names(*scenario_descriptor(scenario));
    if (std::find(choices.begin(), choices.end(), v.get<std::string>()) != choices.end()) return;
    reject(name, "expects one of " + comma_joined(choices) + ", got " + json_excerpt(v));
  };
  return k;
}

// The agent's initialisation scheme by its name (core/mlp.hpp, WeightInit); absent: ddpg.
ConfigKey init_key() {
  const std::string name = "init";
  ConfigKey k{name, ConfigPart::kAgent, "one of " + comma_joined(weight_init_names()), kAnyNumber,
              "how every network's Linear layers start: ddpg (Lillicrap et al. 2016: U(±1/√fan_in), the last "
              "layer U(±3e-3); the paper's five), xavier (Glorot-uniform weights, zero biases: ikostrikov/rlpd's "
              "default_init; rlpd-sac's recipe), pytorch (torch.nn.Linear's default, U(±1/√fan_in) for weights and "
              "biases of every layer: sfujim/TD3_BC; td3-bc's recipe); absent: ddpg",
              nullptr, {}, {}, {}, {}};
  k.read = [name](const nlohmann::json& v, RunConfig& config) {
    const std::optional<WeightInit> scheme = v.is_string() ? weight_init_from_name(v.get<std::string>()) : std::nullopt;
    if (!scheme) reject(name, "expects one of " + comma_joined(weight_init_names()) + ", got " + json_excerpt(v));
    config.agent.init = *scheme;
  };
  k.write = [](const RunConfig& config) { return nlohmann::json(weight_init_name(config.agent.init)); };
  k.set_neutral = [](RunConfig& config) { config.agent.init = WeightInit::kDdpg; };
  return k;
}

// What a method key's doc line ends with: the recipes that set it, and the value a config that
// leaves it out gets (when that value is one the key accepts; otherwise the doc says "not given").
std::string method_key_suffix(const MethodKey& m) {
  std::vector<std::string> recipes;
  for (const Algorithm& a : algorithms())
    for (const auto& [key, value] : a.recipe)
      if (key == m.name) recipes.push_back(a.name + " " + value.dump());
  std::string text;
  if (!recipes.empty()) text += std::string(recipes.size() == 1 ? "; recipe: " : "; recipes: ") + comma_joined(recipes);
  if (m.neutral && m.bounds.contains(*m.neutral)) {
    const double v = *m.neutral;
    text += "; absent: " + (v == std::trunc(v) ? std::to_string(static_cast<long long>(v)) : nlohmann::json(v).dump());
  }
  return text;
}

// A method key's row (algos/method_key.hpp): its value goes to AgentConfig::method.
ConfigKey method_key_row(const MethodKey& m) {
  const std::string type = m.type == MethodKey::kInteger ? type_name<int>() : type_name<float>();
  ConfigKey k{m.name, ConfigPart::kAgent, type, m.bounds, std::string(m.doc) + method_key_suffix(m), nullptr, {}, {}, {}, {}};
  // `m` is one of the algorithms' static declarations, so the row may hold on to it.
  k.read = [&m](const nlohmann::json& v, RunConfig& config) {
    const double x = m.type == MethodKey::kInteger ? typed<int>(m.name, v) : typed<float>(m.name, v);
    check_bounds(m.name, m.bounds, x, v);
    config.agent.method.set(m, x);
  };
  k.write = [&m](const RunConfig& config) {
    return m.type == MethodKey::kInteger ? nlohmann::json(config.agent.method.integer(m))
                                         : nlohmann::json(config.agent.method.number(m));
  };
  if (m.neutral) k.set_neutral = [&m](RunConfig& config) { config.agent.method.erase(m.name); };
  return k;
}

// `keys` with a row for every algorithm's method key after the backbone's agent keys (after
// noise_std), in the registry's order.
std::vector<ConfigKey> with_method_keys(std::vector<ConfigKey> keys) {
  auto at = std::find_if(keys.begin(), keys.end(), [](const ConfigKey& k) { return k.name == "noise_std"; }) + 1;
  for (const MethodKey* m : method_keys()) at = keys.insert(at, method_key_row(*m)) + 1;
  return keys;
}

}  // namespace

const char* part_name(ConfigPart part) {
  switch (part) {
    case ConfigPart::kAgent: return "agent";
    case ConfigPart::kSchedule: return "schedule";
    case ConfigPart::kScenario: return "scenario";
  }
  return "?";
}

std::string ConfigKey::accepts() const {
  const std::string b = bounds.text();
  if (b.empty()) return type;
  return type + (type.starts_with("list") ? ", each " : ", ") + b;
}

const std::vector<ConfigKey>& config_keys() {
  static const std::vector<ConfigKey> keys = with_method_keys({
      key("actor_hidden", &AgentConfig::actor_hidden, kPositive, "hidden layer widths of the actor (tanh output)"),
      key("critic_hidden", &AgentConfig::critic_hidden, kPositive,
          "hidden layer widths of the critic, LayerNorm after each unless critic_layer_norm is false"),
      optional_key("critic_layer_norm", &AgentConfig::critic_layer_norm, kAnyNumber, true,
                   "LayerNorm after each hidden layer of every critic (the paper's §III-B2 and ikostrikov/rlpd's "
                   "critic_layer_norm); td3-bc's recipe: false (sfujim/TD3_BC's critics have none); absent: true"),
      init_key(),
      key("actor_lr", &AgentConfig::actor_lr, kPositive, "Adam learning rate of the actor"),
      key("critic_lr", &AgentConfig::critic_lr, kPositive, "Adam learning rate of the critic"),
      key("gamma", &AgentConfig::gamma, {.lo = 0, .hi = 1, .hi_open = true}, "discount factor γ"),
      key("tau", &AgentConfig::tau, {.lo = 0, .hi = 1, .lo_open = true}, "Polyak rate τ of the target networks"),
      key("batch_size", &AgentConfig::batch_size, at_least(2),
          "batch size B; with a prior dataset B/2 prior + B/2 online"),
      key("noise_std", &AgentConfig::noise_std, kNonNegative,
          "std of the Gaussian exploration noise added to the [-1, 1] action"),
      key("steps", &RunConfig::steps, kPositive, "environment decisions of training"),
      key("warmup_steps", &RunConfig::warmup_steps, kNonNegative,
          "decisions of uniform-random actions, without updates, before learning starts; 0: none, π(s) + noise "
          "from the first decision (Algorithm 1). Updates start at the first decision after the warm-up at which "
          "the online buffer holds a batch's online part (B/2 with a prior dataset, B without)"),
      key("eval_every", &RunConfig::eval_every, kPositive,
          "evaluate at the first episode boundary after every multiple of this many decisions"),
      key("eval_episodes", &RunConfig::eval_episodes, kPositive,
          "episodes per evaluation: deterministic policy, fixed evaluation seeds"),
      key("last_k", &RunConfig::last_k, kPositive,
          "without a final evaluation, the final return is the mean of the last K evaluations"),
      optional_key("final_eval_episodes", &RunConfig::final_eval_episodes, kNonNegative, 0,
                   "episodes of the final evaluation at the end of training (the evaluation seeds of every "
                   "evaluation, more of them), whose mean is the final return; absent or 0: none"),
      key("bc_log_every", &RunConfig::bc_log_every, kPositive,
          "decisions per point of the logged loss curves (mean over the window's updates)"),
      key("buffer_capacity", &RunConfig::buffer_capacity, kPositive,
          "capacity of the online replay buffer (a run stores at most `steps` transitions)"),
      descriptor_choice_key("network", &ScenarioSettings::network, "a network of the scenario",
                            "road geometry, one of the scenario file's networks: the built-ins' short road or "
                            "their 4.5 km long one (docs/scenarios.md)",
                            scenario_network_names),
      key("action_repeat", &ScenarioSettings::action_repeat, setting_range::kActionRepeat,
          "SUMO steps of 0.1 s per decision", driving_only),
      key("horizon", &ScenarioSettings::horizon, setting_range::kHorizon, "decisions per episode", driving_only),
      key("lane_change_interval", &ScenarioSettings::lane_change_interval, setting_range::kLaneChangeInterval,
          "decisions the ego waits between two lane changes", driving_only),
      key("traffic_warmup", &ScenarioSettings::traffic_warmup, setting_range::kTrafficWarmup,
          "SUMO steps of traffic before the ego enters (plus a random 0 to 50)", driving_only),
      key("max_depart_delay", &ScenarioSettings::max_depart_delay, setting_range::kMaxDepartDelay,
          "seconds a vehicle may queue to enter before SUMO drops it; -1: no limit", driving_only),
      key("desired_speed", &ScenarioSettings::desired_speed, setting_range::kDesiredSpeed,
          "v_des of the reward, m/s (SUMO's driver aims at it too)", driving_only),
      descriptor_choice_key("reward", &ScenarioSettings::reward, "a reward variant of the scenario",
                            "reward variant: short, flow (per-step terms of docs/scenarios.md) or one the scenario "
                            "file defines",
                            scenario_reward_names),
      key("inflow", &ScenarioSettings::inflow, setting_range::kInflow,
          "offered inflow per main-road lane, veh/h (Bernoulli, one draw per second)", driving_only),
      key("ramp_inflow", &ScenarioSettings::ramp_inflow, setting_range::kRampInflow, "inflow on the on-ramp, veh/h",
          merge_only),
      key("obstacles", &ScenarioSettings::obstacles, setting_range::kObstacles, "slow obstacle vehicles on the road",
          cut_in_only),
      key("obstacle_speed_min", &ScenarioSettings::obstacle_speed_min, setting_range::kObstacleSpeed,
          "lowest obstacle speed, m/s (each obstacle draws its own)", cut_in_only),
      key("obstacle_speed_max", &ScenarioSettings::obstacle_speed_max, setting_range::kObstacleSpeed,
          "highest obstacle speed, m/s", cut_in_only),
  });
  return keys;
}

const ConfigKey* find_config_key(const std::string& name, const std::vector<ConfigKey>& keys) {
  for (const ConfigKey& k : keys)
    if (k.name == name) return &k;
  return nullptr;
}

}  // namespace rapid
