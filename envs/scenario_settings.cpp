#include "envs/scenario_settings.hpp"

#include "envs/scenario_descriptor.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace rapid {

const std::vector<std::string>& reward_variants() {
  static const std::vector<std::string> names = {"short", "flow"};
  return names;
}

ScenarioSettings default_scenario_settings(const std::string& scenario) {
  if (scenario == "pendulum") throw std::invalid_argument("'" + scenario + "' is not a driving scenario");
  return scenario_descriptor(scenario)->defaults;
}

namespace {
void require(bool ok, const std::string& message) {
  if (!ok) throw std::invalid_argument(message);
}
bool one_of(const std::string& v, const std::vector<std::string>& names) {
  return std::find(names.begin(), names.end(), v) != names.end();
}
std::string list(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}
}  // namespace

void validate_scenario_settings(const std::string& scenario, const ScenarioSettings& s) {
  validate_scenario_settings(*scenario_descriptor(scenario), s);
}

void validate_scenario_settings(const ScenarioDescriptor& d, const ScenarioSettings& s) {
  const std::string& scenario = d.name;
  std::vector<std::string> networks;
  for (const auto& [variant, files] : d.networks) networks.push_back(variant);
  require(one_of(s.network, networks), "network: '" + s.network + "' is not one of " + list(networks));
  std::vector<std::string> rewards = reward_variants();
  for (const auto& [name, weights] : d.rewards) rewards.push_back(name);
  require(one_of(s.reward, rewards), "reward: '" + s.reward + "' is not one of " + list(rewards));
  require(s.action_repeat >= 1 && s.action_repeat <= 50, "action_repeat: must be 1 to 50 SUMO steps");
  require(s.horizon >= 1 && s.horizon <= 100000, "horizon: must be 1 to 100000 decisions");
  require(s.lane_change_interval >= 0 && s.lane_change_interval <= 10000, "lane_change_interval: must be 0 to 10000");
  require(s.traffic_warmup >= 0 && s.traffic_warmup <= 100000, "traffic_warmup: must be 0 to 100000 SUMO steps");
  require(std::isfinite(s.max_depart_delay) && s.max_depart_delay >= -1.0 && s.max_depart_delay <= 3600.0,
          "max_depart_delay: must be -1 (no limit) or 0 to 3600 s");
  require(std::isfinite(s.desired_speed) && s.desired_speed >= 1.0 && s.desired_speed <= 35.0,
          "desired_speed: must be 1 to 35 m/s");
  // One Bernoulli draw per lane per second: at most 3600 veh/h per lane.
  require(std::isfinite(s.inflow) && s.inflow >= 0.0 && s.inflow <= 3600.0, "inflow: must be 0 to 3600 veh/h per lane");
  const bool merge = d.has_ramp_inflow, cut_in = d.hook == kCutInObstaclesHook;
  require(std::isfinite(s.ramp_inflow) && s.ramp_inflow >= 0.0 && s.ramp_inflow <= 3600.0,
          "ramp_inflow: must be 0 to 3600 veh/h");
  require(merge || s.ramp_inflow == 0.0, "ramp_inflow: scenario '" + scenario + "' has no on-ramp");
  if (cut_in) {
    require(s.obstacles >= 0 && s.obstacles <= 100, "obstacles: must be 0 to 100");
    require(std::isfinite(s.obstacle_speed_min) && s.obstacle_speed_min > 0.0,
            "obstacle_speed_min: must be positive");
    require(std::isfinite(s.obstacle_speed_max) && s.obstacle_speed_max >= s.obstacle_speed_min &&
                s.obstacle_speed_max <= 35.0,
            "obstacle_speed_max: must be at least obstacle_speed_min and at most 35 m/s");
  } else {
    require(s.obstacles == 0 && s.obstacle_speed_min == 0.0 && s.obstacle_speed_max == 0.0,
            "obstacles: scenario '" + scenario + "' has no obstacles");
  }
}

}  // namespace rapid
