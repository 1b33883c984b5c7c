#include "envs/scenario_settings.hpp"

#include "core/printable.hpp"
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
}  // namespace

void validate_scenario_settings(const std::string& scenario, const ScenarioSettings& s) {
  validate_scenario_settings(*scenario_descriptor(scenario), s);
}

void validate_scenario_settings(const ScenarioDescriptor& d, const ScenarioSettings& s) {
  const std::string& scenario = d.name;
  const std::vector<std::string> networks = scenario_network_names(d);
  require(one_of(s.network, networks), "network: '" + s.network + "' is not one of " + comma_joined(networks));
  const std::vector<std::string> rewards = scenario_reward_names(d);
  require(one_of(s.reward, rewards), "reward: '" + s.reward + "' is not one of " + comma_joined(rewards));
  const auto in_range = [](const char* key, double x, const Bounds& range) {
    require(std::isfinite(x) && range.contains(x), std::string(key) + ": must be " + range.text());
  };
  namespace r = setting_range;
  in_range("action_repeat", s.action_repeat, r::kActionRepeat);
  in_range("horizon", s.horizon, r::kHorizon);
  in_range("lane_change_interval", s.lane_change_interval, r::kLaneChangeInterval);
  in_range("traffic_warmup", s.traffic_warmup, r::kTrafficWarmup);
  in_range("max_depart_delay", s.max_depart_delay, r::kMaxDepartDelay);
  in_range("desired_speed", s.desired_speed, r::kDesiredSpeed);
  in_range("inflow", s.inflow, r::kInflow);
  in_range("ramp_inflow", s.ramp_inflow, r::kRampInflow);
  require(d.has_ramp_inflow || s.ramp_inflow == 0.0, "ramp_inflow: scenario '" + scenario + "' has no on-ramp");
  if (d.hook == kCutInObstaclesHook) {
    in_range("obstacles", s.obstacles, r::kObstacles);
    in_range("obstacle_speed_min", s.obstacle_speed_min, r::kObstacleSpeed);
    in_range("obstacle_speed_max", s.obstacle_speed_max, r::kObstacleSpeed);
    require(s.obstacle_speed_max >= s.obstacle_speed_min,
            "obstacle_speed_max: must be at least obstacle_speed_min");
  } else {
    require(s.obstacles == 0 && s.obstacle_speed_min == 0.0 && s.obstacle_speed_max == 0.0,
            "obstacles: scenario '" + scenario + "' has no obstacles");
  }
}

}  // namespace rapid
