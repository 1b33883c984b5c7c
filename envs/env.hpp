// The environment interface every task implements: the SUMO driving scenarios and the SUMO-free
// pendulum. Observations are written into a caller-owned vector so that a step
// allocates nothing.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/tensor.hpp"
#include "envs/driving_reward.hpp"
#include "envs/scenario_settings.hpp"

namespace rapid {

struct Trace;  // envs/trace.hpp

struct StepInfo {
  bool collision = false;
  double ego_speed = 0.0;       // m/s (pendulum: angular velocity)
  int lane_changes = 0;         // lane changes completed during this decision
  bool lane_change_failed = false;  // a commanded lane change that could not happen
  // A driving scenario's reward term by term (reward_terms.total is the reward); all zero for the
  // pendulum. What a trace records per decision, and what the Python module's step info gives.
  driving::RewardTerms reward_terms;
};

struct StepResult {
  float reward = 0.0f;
  bool terminated = false;  // true end of the episode (collision): no bootstrapping
  bool truncated = false;   // time limit reached: bootstrap through it
  StepInfo info;
};

// Every entry of every observation lies in [-kObservationBound, kObservationBound]: each
// environment's observe() normalises and clips into it (driving_env.cpp, pendulum.cpp). The
// observation space a Gymnasium environment or a Minari dataset declares.
inline constexpr float kObservationBound = 1.0f;

class Env {
 public:
  virtual ~Env() = default;

  virtual std::string name() const = 0;
  virtual int obs_dim() const = 0;
  virtual int act_dim() const = 0;
  // Decisions per episode before truncation.
  virtual int horizon() const = 0;

  // Starts a new episode whose randomness is fully determined by `seed`; writes s_0 into `obs`.
  virtual void reset(std::uint64_t seed, VecRef obs) = 0;
  // Applies `action` (each entry in [-1, 1]; clipped) for one decision; writes s_{t+1} into `obs`.
  virtual StepResult step(const ConstVecRef& action, VecRef obs) = 0;

  // Lets the simulator's own driver control the agent (the `sumo` reference policy); actions
  // passed to step() are then ignored. Environments without such a driver throw.
  virtual void set_builtin_driver(bool on);

  // Records every following reset() and step() into `trace` (nullptr: stop): the road once, then
  // per episode its start and per decision the action, the reward's terms and the vehicles around
  // the agent (docs/traces.md). The trace must outlive the recording. Environments without a road
  // throw std::invalid_argument.
  virtual void record(Trace* trace);
};

// Names accepted by make_env: the built-in driving scenarios (builtin_scenario_names(), by name),
// then the pendulum.
std::vector<std::string> env_names();
// Throws std::invalid_argument("unknown scenario '…'; expected one of … or a scenario file (.json)",
// naming where the built networks were looked for if there are none) unless `name` is a built-in
// scenario, a scenario file or a name a grid registered for one.
void check_scenario_name(const std::string& name);
// Throws std::invalid_argument("unknown scenario '…'; expected one of …") for an unknown name.
// Driving scenarios get their `short` profile settings.
std::unique_ptr<Env> make_env(const std::string& name);
// A driving scenario with the given settings (throws std::invalid_argument naming a bad setting,
// or for the pendulum, which has none).
std::unique_ptr<Env> make_env(const std::string& name, const ScenarioSettings& settings);
// For a scenario file: starts it in SUMO with `settings`, resets and takes one decision, so that a
// file SUMO cannot run (a network that is no SUMO net, a route the ego cannot drive, a step length
// SUMO refuses) is refused before a command writes anything. Throws std::invalid_argument("scenario
// file F does not run in SUMO: <SUMO's first line>"); SUMO's own messages are kept off stderr.
// Built-in scenarios and the pendulum are not probed (their files ship with the harness and are tested).
void check_scenario_runs(const std::string& name, const ScenarioSettings& settings);
// The built-in driving scenarios and scenario files (a path, or a name a grid registered): the
// scenarios that take ScenarioSettings.
bool is_driving_scenario(const std::string& name);
// One of env_names(): shipped with the harness, not a scenario file.
bool is_builtin_scenario(const std::string& name);

}  // namespace rapid
