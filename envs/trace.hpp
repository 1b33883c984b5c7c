// A recorded rollout ("rapid.trace/1", docs/traces.md): the road's geometry once, then per episode
// the state it started in and, per decision, the agent's action, the reward and its terms, and the
// position, lane, speed and size of every vehicle within the sensing range. SUMO-free: a driving
// env fills it while recording (Env::record), `rapid rollout --record` writes it, and
// `scripts/plot animate` draws it.
//
// The JSON is written with fixed number formats and no timestamps, paths of this machine or host
// names, so the same command with the same seed writes a byte-identical file.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "envs/driving_reward.hpp"
#include "envs/scenario_settings.hpp"

namespace rapid {

inline constexpr const char* kTraceSchema = "rapid.trace/1";

// One vehicle as SUMO reports it: x, y are its front bumper's position (m), angle its heading in
// SUMO's convention (degrees, 0 = north, clockwise).
struct TraceVehicle {
  std::string id, type, lane;  // lane: SUMO lane id, "<edge>_<index>"
  double x = 0, y = 0, angle = 0, speed = 0, length = 0, width = 0;
};

// The ego and every other vehicle whose front is within the sensing range of the ego's front.
struct TraceSnapshot {
  double time = 0;  // simulation time, s
  TraceVehicle ego;
  std::vector<TraceVehicle> vehicles;
};

struct TraceDecision {
  int t = 0;                         // decision index within the episode (0 = the first)
  std::optional<std::array<float, 2>> action;  // as the policy gave it; none under SUMO's driver
  double accel = 0;                  // the ego's realised acceleration over the decision, m/s²
  float reward = 0;                  // what the agent received
  driving::RewardTerms terms;        // how that reward came about (terms.total == reward)
  int lane_changes = 0;
  bool lane_change_failed = false, collision = false, terminated = false, truncated = false;
  TraceSnapshot state;               // after the decision
};

struct TraceEpisode {
  int index = 0;               // the episode's index in the rollout
  std::uint64_t env_seed = 0;  // the seed its reset() got
  TraceSnapshot start;         // after reset(), before the first decision
  std::vector<TraceDecision> decisions;
  double ret = 0;              // the return the rollout reported (sum of the rewards, in order)
  bool collision = false;
};

struct TraceLane {
  std::string id;
  int index = 0;
  double width = 0, length = 0;
  std::vector<std::array<double, 2>> shape;  // centre line, x/y in m
};

struct TraceEdge {
  std::string id;
  std::vector<TraceLane> lanes;
};

// Where edges meet (SUMO's junction polygons): the road surface between one edge's end and the
// next one's start.
struct TraceJunction {
  std::string id;
  std::vector<std::array<double, 2>> shape;
};

struct Trace {
  // Filled by the env.
  std::string scenario;
  ScenarioSettings settings;
  double step_length = 0.1;       // s per SUMO step
  double sensing_range = 100.0;   // m
  driving::RewardWeights reward_weights;
  std::vector<TraceEdge> road;
  std::vector<TraceJunction> junctions;
  std::vector<TraceEpisode> episodes;
  // Filled by whoever runs the policy.
  std::string policy;             // random | zero | sumo | the checkpoint as given
  std::uint64_t seed = 0;
  std::string traffic = "seed";   // "seed": reset seeds come from `seed`; "evaluation": the trainer's

  double decision_seconds() const { return settings.action_repeat * step_length; }
};

// The trace as "rapid.trace/1" JSON (docs/traces.md); deterministic.
std::string trace_to_json(const Trace& trace);

}  // namespace rapid
