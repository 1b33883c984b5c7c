// The knobs of a driving scenario that a run's config may set: control rate, horizon, traffic,
// obstacles, the desired speed and the reward variant. The defaults are the `short` profile (the
// scenarios as first built: 0.5 s decisions, 150 per episode); the `flow` profile sets them to the
// paper's scale (docs/scenarios.md). A test holds the short profile's configs to these defaults.
#pragma once

#include <string>
#include <vector>

#include "core/bounds.hpp"

namespace rapid {

struct ScenarioSettings {
  // Geometry: one of the descriptor's networks (the built-ins: "short", envs/networks/<scenario>/,
  // and "long", envs/networks/<scenario>/long/).
  std::string network = "short";
  int action_repeat = 5;           // SUMO steps of 0.1 s per decision
  int horizon = 150;               // decisions per episode
  int lane_change_interval = 4;    // decisions between two lane changes of the ego
  int traffic_warmup = 250;        // SUMO steps of traffic before the ego enters (+ up to 50)
  // Seconds a vehicle may wait to enter the road before SUMO drops it (< 0: no limit). An inflow
  // above what the entry passes otherwise builds an ever longer queue of waiting vehicles that
  // SUMO retries every step, which costs time and changes nothing on the road.
  double max_depart_delay = -1.0;
  double desired_speed = 25.0;     // v_des of the reward, m/s (SUMO's driver aims at it too)
  std::string reward = "short";    // reward variant: "short" or "flow" (envs/driving_reward.hpp)
  // Offered inflow per main-road lane, veh/h (each lane a Bernoulli flow, one draw per second).
  double inflow = 0.0;
  double ramp_inflow = 0.0;        // roads with a RAMP_INFLOW flow (merge): veh/h on the on-ramp
  int obstacles = 0;               // roads with the cut-in-obstacles hook: slow obstacle vehicles
  double obstacle_speed_min = 0.0, obstacle_speed_max = 0.0;  // with that hook, m/s
};

// The values each numeric setting accepts: validate_scenario_settings checks them, and the
// config-key table declares them (experiments/run/config_keys.cpp), from this one place.
namespace setting_range {
inline constexpr Bounds kActionRepeat{.lo = 1, .hi = 50};          // SUMO steps
inline constexpr Bounds kHorizon{.lo = 1, .hi = 100000};           // decisions
inline constexpr Bounds kLaneChangeInterval{.lo = 0, .hi = 10000};  // decisions
inline constexpr Bounds kTrafficWarmup{.lo = 0, .hi = 100000};     // SUMO steps
inline constexpr Bounds kMaxDepartDelay{.lo = -1, .hi = 3600};     // s; negative: no limit
inline constexpr Bounds kDesiredSpeed{.lo = 1, .hi = 35};          // m/s
// One Bernoulli draw per lane per second: at most 3600 veh/h per lane.
inline constexpr Bounds kInflow{.lo = 0, .hi = 3600};              // veh/h per lane
inline constexpr Bounds kRampInflow{.lo = 0, .hi = 3600};          // veh/h
inline constexpr Bounds kObstacles{.lo = 0, .hi = 100};
inline constexpr Bounds kObstacleSpeed{.lo = 0, .hi = 35, .lo_open = true};  // m/s, min and max
}  // namespace setting_range

struct ScenarioDescriptor;

// The `short` profile's settings of a driving scenario: its descriptor's defaults (throws
// std::invalid_argument for a name that is not a driving scenario).
ScenarioSettings default_scenario_settings(const std::string& scenario);

// Throws std::invalid_argument("<key> …") naming the first setting that is out of range for
// the scenario (e.g. obstacles on a road without them, a minimum above a maximum, a network the
// descriptor does not have).
void validate_scenario_settings(const ScenarioDescriptor& scenario, const ScenarioSettings& s);
void validate_scenario_settings(const std::string& scenario, const ScenarioSettings& s);

// The reward variants a setting may name.
const std::vector<std::string>& reward_variants();

}  // namespace rapid
