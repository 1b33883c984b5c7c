// A SUMO driving scenario (docs/scenarios.md): one agent-controlled ego among SUMO-driven humans, on
// the road its descriptor (envs/scenario_descriptor.hpp) describes: the network, where the ego
// enters, the observation's extra features, and a named hook for what else a task puts on the
// road (envs/scenario_hooks.hpp).
//
// Decision: a = (a0, a1) ∈ [-1,1]², held for `action_repeat` SUMO steps of 0.1 s.
//   a0·max_accel is the commanded acceleration, applied by a setSpeed before each SUMO step of the
//   decision (speed clipped to [0, speed_norm]); speed mode 0 (no safety checks) lets the ego make
//   mistakes.
//   a1 < −θ → one lane right, a1 > θ → one lane left (θ the descriptor's lane_change_threshold, 1/3), through changeLane with the ego's own
//   lane changing off (lane-change mode 256: only TraCI requests, refused only if they would
//   overlap a vehicle). A request into a missing lane, before `lane_change_interval` decisions have
//   passed since the last change, or refused by SUMO is a failed lane change: penalised, no effect.
// Observation (every entry in [-1, 1]; docs/scenarios.md):
//   [0] ego speed 2v/v_norm − 1, [1] lane change allowed (+1) or still in its minimum interval (−1),
//   then for each of the descriptor's neighbour lanes (left, current, right by default; 5 each): leader gap / R (missing +1), leader
//   relative speed / 15 m/s (missing +1), −follower gap / R (missing −1), follower relative
//   speed / 15 m/s (missing −1), lane continues ahead (−1 missing, 2·min(1, d_end / R_end) − 1);
//   then the descriptor's features.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/rng.hpp"
#include "envs/driving_reward.hpp"
#include "envs/env.hpp"
#include "envs/road.hpp"
#include "envs/scenario_descriptor.hpp"
#include "envs/scenario_settings.hpp"
#include "envs/sumo_session.hpp"

namespace rapid {

struct Trace;
struct TraceSnapshot;

RAPID_SUMO_BACKEND_BEGIN

class ScenarioHook;

class DrivingEnv final : public Env {
 public:
  static constexpr int kCommonObs = 17;  // the entries before the features, with all three lanes
  static constexpr const char* kEgo = "ego";

  // Throws std::invalid_argument naming a setting out of range for the scenario.
  DrivingEnv(std::shared_ptr<const ScenarioDescriptor> scenario, const ScenarioSettings& settings);
  ~DrivingEnv() override;

  std::string name() const override { return scenario_->name; }
  int obs_dim() const override { return features_at() + static_cast<int>(scenario_->features.size()); }
  // Where the descriptor's features start in the observation.
  int features_at() const { return 2 + 5 * static_cast<int>(scenario_->neighbour_lanes.size()); }
  int act_dim() const override { return 2; }
  int horizon() const override { return settings_.horizon; }
  void reset(std::uint64_t seed, VecRef obs) override;
  StepResult step(const ConstVecRef& action, VecRef obs) override;
  void set_builtin_driver(bool on) override { builtin_ = on; }
  // The temporary routes file SUMO reads (the scenario's with the configured inflows), made at the
  // first reset under a random name and removed with the env; empty before.
  const std::string& route_file() const { return route_file_; }
  // Recording (envs/driving_trace.cpp): with a trace attached, reset() adds an episode (and the
  // road, once) and step() a decision; with none, neither reads anything extra from SUMO.
  void record(Trace* trace) override;

  // Runs SUMO as `binary` with `extra_args` appended to its command line, from the next reset on
  // (the libtraci build runs sumo-gui this way: envs/gui_env.cpp).
  void set_sumo_binary(std::string binary, std::vector<std::string> extra_args) {
    session_config_.binary = std::move(binary);
    session_config_.extra_args = std::move(extra_args);
  }

  // Advances the running simulation by `sumo_steps` SUMO steps and nothing else: no ego command,
  // no state read, no observation or reward. This is the raw cost of the network and traffic the
  // env wraps, the baseline `rapid bench` holds step() against (reset with the built-in driver
  // first, so SUMO drives the ego as one more vehicle). It ends the episode: reset() before the
  // next step().
  void advance_traffic_only(int sumo_steps);

  // What the env read from SUMO at the end of the last decision (also for tests).
  struct Neighbor {
    bool present = false;
    std::string id;
    double gap = 0.0;    // bumper to bumper, m
    double speed = 0.0;  // m/s
  };
  struct EgoState {
    int edge = -1;  // index into road()
    int lane = 0;   // lane index on that edge
    int global_lane = 0;
    double pos = 0.0, progress = 0.0, speed = 0.0;
    Neighbor leader[3], follower[3];  // left, current, right lane
  };
  const EgoState& ego() const { return ego_; }
  const Road& road() const { return road_; }
  // Id of the edge the ego is on ("" before the first reset).
  const std::string& ego_edge() const {
    static const std::string none;
    return ego_.edge < 0 ? none : road_.edge(ego_.edge).id;
  }
  const ScenarioDescriptor& scenario() const { return *scenario_; }
  const ScenarioSettings& settings() const { return settings_; }
  const driving::RewardWeights& reward_weights() const { return weights_; }
  // The scenario's hook (nullptr without one), e.g. for a test to read what it did.
  const ScenarioHook* hook() const { return hook_.get(); }

 private:
  // A descriptor feature with its geometry resolved on the road (once, at the first reset).
  struct Feature {
    FeatureSpec::Kind kind;
    double target = 0.0;  // progress of the edge's start, or of the lane's end
    double range = 1.0;
    int global_lane = 0;
  };
  void resolve_features();
  int ego_depart_lane(Rng& rng) const;
  void write_features(float* out) const;
  void read_state();
  void read_neighbors(int side, int mode_leaders, int mode_followers);
  bool ego_collided() const;
  bool ego_at_dead_end() const;
  // Out of line and opaque to the optimiser, so the reward's arithmetic is the same code whether
  // or not the caller reads the terms (a recorded episode gets the very rewards of an unrecorded one).
  [[gnu::noipa]] driving::RewardTerms reward(bool collision, bool changed_lane, bool failed_change) const;
  void record_road();
  void record_reset(std::uint64_t seed);
  void record_snapshot(TraceSnapshot& snapshot) const;
  void record_decision(const ConstVecRef& action, double speed_before, const StepResult& r,
                       const driving::RewardTerms& terms);
  void observe(VecRef obs) const;

  std::shared_ptr<const ScenarioDescriptor> scenario_;
  ScenarioSettings settings_;
  std::unique_ptr<ScenarioHook> hook_;
  std::vector<Feature> features_;
  SessionConfig session_config_;
  SumoSession session_;
  Road road_;
  bool road_read_ = false;
  bool builtin_ = false;
  EgoState ego_;
  std::string road_id_;  // reused buffer for getRoadID
  int t_ = 0;
  int since_lane_change_ = 0;
  bool episode_over_ = true;
  driving::IdmGap idm_;
  driving::RewardWeights weights_;
  std::string route_file_;  // this env's routes with the configured inflows (a temporary file)
  Trace* trace_ = nullptr;  // recording into it when set
};

// A built-in scenario (lane-drop, cut-in, merge) or a descriptor file, in this backend's build
// (throws std::invalid_argument for any other name, a bad descriptor or bad settings).
std::unique_ptr<DrivingEnv> make_driving_env(const std::string& name, const ScenarioSettings& settings);

RAPID_SUMO_BACKEND_END
}  // namespace rapid
