// A driving scenario as data (docs/scenarios.md §Scenario files): a JSON descriptor names the SUMO
// network and routes, the road the ego drives, where and how the ego enters, the observation's
// extra features, the action mapping, the default settings and, where a task needs behaviour that
// data cannot say, a named C++ hook (envs/scenario_hooks.hpp). The built-in scenarios are such
// files (envs/networks/<scenario>/scenario.json); `--scenario FILE.json` runs a user's own.
//
// Reading a descriptor checks everything that can be checked without starting SUMO: the files
// exist, the road's edges are in the network, the ego's route is in the routes and starts on the
// road, every field has its type and range. Any problem is one std::invalid_argument line naming
// the file and the field.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "envs/driving_reward.hpp"
#include "envs/scenario_settings.hpp"

namespace rapid {

// One extra observation entry in [-1, 1], computed from the road's geometry and the ego's place.
struct FeatureSpec {
  enum class Kind {
    // 2·min(1, d / range) − 1 for the distance d to the start of `edge`; +1 once there.
    kDistanceToEdge,
    // While the ego is on `lane` of `edge` (counted across the road, as the road lines lanes up):
    // 2·clamp(d / range, 0, 1) − 1 for the distance d to where that lane ends; +1 off that lane.
    // range is `range` metres, or the distance from the start of `range_from` to the lane's end.
    kDistanceToLaneEnd,
  };
  Kind kind = Kind::kDistanceToEdge;
  std::string edge;
  int lane = 0;
  double range = 0.0;      // m; 0 with kDistanceToLaneEnd: taken from range_from
  std::string range_from;  // an edge of the road (kDistanceToLaneEnd only)
};

// The feature kinds by their descriptor name.
const std::vector<std::string>& feature_kind_names();

struct NetworkFiles {
  std::string net;     // the netconvert-built .net.xml
  std::string routes;  // routes and flows; probability="INFLOW" / "RAMP_INFLOW" take the settings
};

struct ScenarioDescriptor {
  std::string file;  // the descriptor's path (absolute, normal form)
  std::string name;
  std::string display_name;
  // The geometries a run's `network` setting chooses from (e.g. "short", "long"), their files as
  // absolute paths.
  std::map<std::string, NetworkFiles> networks;
  std::vector<std::string> additional_files;  // vehicle types and other SUMO additionals
  // The edges of the one straight road, the first anchoring the progress coordinate.
  std::vector<std::string> road;
  struct Ego {
    std::string route;        // a route of the routes file
    std::string depart_edge;  // the route's first edge (read from the routes file)
    std::string type = "ego";
    int depart_lane = -1;     // a lane of depart_edge, or -1: a random lane each episode
  } ego;
  double step_length = 0.1;        // s per SUMO step
  int traffic_warmup_jitter = 50;  // up to this many SUMO steps of warm-up more, drawn per episode
  // The observation (envs/driving_env.hpp): the common 17 entries, then `features`.
  double sensing_range = 100.0;   // R (m): vehicles farther away read as missing
  double lane_end_range = 200.0;  // R_end (m) of the "lane continues ahead" entries
  double speed_norm = 35.0;       // v_norm (m/s): also the ego's top speed under agent control
  double rel_speed_norm = 15.0;   // m/s
  // The lanes whose leader and follower the observation holds, 5 entries each, in the order
  // left, current, right: side 0 = left, 1 = the ego's lane, 2 = right (default all three).
  std::vector<int> neighbour_lanes = {0, 1, 2};
  std::vector<FeatureSpec> features;
  // The action: a0·max_accel m/s²; a1 beyond ±lane_change_threshold asks for a lane change.
  double max_accel = 4.0;
  float lane_change_threshold = 1.0f / 3.0f;
  std::string hook;  // "" or one of scenario_hook_names()
  // Reward variants of the scenario's own, by name, beside the built-in short and flow
  // (envs/driving_reward.hpp): the `reward` setting may name one.
  std::map<std::string, driving::RewardWeights> rewards;
  // What a setting left unset is (the settings a run's config does not give).
  ScenarioSettings defaults;
  bool has_ramp_inflow = false;  // a routes file has a RAMP_INFLOW flow: `ramp_inflow` applies
  // Per config profile, the config keys that differ from the profile's shared keys and from the
  // settings above (e.g. {"flow": {"steps": 30000, "network": "long"}}); checked when a run
  // resolves its config (experiments/run/run_config.hpp).
  nlohmann::json profiles = nlohmann::json::object();
};

// What a run's `network` setting may name in scenario `d`: its networks' variants.
std::vector<std::string> scenario_network_names(const ScenarioDescriptor& d);
// What a run's `reward` setting may name in scenario `d`: the built-in variants, then its own.
std::vector<std::string> scenario_reward_names(const ScenarioDescriptor& d);

// The names of the observation's neighbour lanes (side 0, 1, 2).
const std::vector<std::string>& neighbour_lane_names();

// The terms of a reward variant a descriptor may weigh (driving::RewardWeights).
const std::vector<std::string>& reward_term_names();

// The weights of the reward variant `name` of scenario `d`: its own, or a built-in one.
driving::RewardWeights scenario_reward_weights(const ScenarioDescriptor& d, const std::string& name);

// The named C++ hooks a descriptor may ask for.
const std::vector<std::string>& scenario_hook_names();
inline constexpr const char* kCutInObstaclesHook = "cut-in-obstacles";
// The vehicle type cut-in-obstacles puts on the road (it must be defined in the scenario's files).
inline constexpr const char* kObstacleType = "obstacle";

// Reads and checks the descriptor at `path` (throws std::invalid_argument "scenario file P:
// <field>: <problem>").
ScenarioDescriptor read_scenario_descriptor(const std::string& path);

// True for a name that stands for a descriptor file rather than a built-in scenario.
bool is_scenario_file(const std::string& name);

// Makes `name` stand for the descriptor at `path` in this process (a grid's "scenario_files", so
// that its jobs, folders and tables use a short name). The descriptor is read and checked; throws
// std::invalid_argument if its own name is not `name`, or `name` is already another file's.
void register_scenario_file(const std::string& name, const std::string& path);
// True for a name register_scenario_file() gave in this process.
bool is_registered_scenario(const std::string& name);

// The descriptor of a built-in scenario (its scenario.json under network_dir()), of a registered
// name, or of a file (`name` ending in .json), read once per process and shared.
std::shared_ptr<const ScenarioDescriptor> scenario_descriptor(const std::string& name);

// A hash of what a scenario file's runs depend on beyond their config: the descriptor and every
// file it names (network, routes, additional files), so that editing any of them makes earlier
// records stale.
std::string scenario_files_hash(const ScenarioDescriptor& d);

// Where the built networks and built-in descriptors live: $RAPID_NETWORK_DIR if set, else the
// build's networks/ folder (compiled in).
std::string network_dir();

// The built-in driving scenarios: every folder of network_dir() that holds a scenario.json (the
// build copies envs/networks/<name>/scenario.json there), by name. No list of them is kept in code.
std::vector<std::string> builtin_scenario_names();

}  // namespace rapid
