// The common part of the three SUMO driving scenarios (docs/scenarios.md): one agent-controlled ego among
// SUMO-driven humans. Scenarios derive from DrivingEnv and supply their network, where the ego
// enters, what else to put on the road, and their own observation features.
//
// Decision: a = (a0, a1) ∈ [-1,1]², held for `action_repeat` SUMO steps of 0.1 s.
//   a0·max_accel is the commanded acceleration, applied by a setSpeed before each SUMO step of the
//   decision (speed clipped to [0, speed_norm]); speed mode 0 (no safety checks) lets the ego make
//   mistakes.
//   a1 < −1/3 → one lane right, a1 > 1/3 → one lane left, through changeLane with the ego's own
//   lane changing off (lane-change mode 256: only TraCI requests, refused only if they would
//   overlap a vehicle). A request into a missing lane, before `lane_change_interval` decisions have
//   passed since the last change, or refused by SUMO is a failed lane change: penalised, no effect.
// Observation (every entry in [-1, 1]; see kCommonObs and docs/scenarios.md):
//   [0] ego speed 2v/v_norm − 1, [1] lane change allowed (+1) or still in its minimum interval (−1),
//   then for the left, current and right lane (5 each): leader gap / R (missing +1), leader
//   relative speed / 15 m/s (missing +1), −follower gap / R (missing −1), follower relative
//   speed / 15 m/s (missing −1), lane continues ahead (−1 missing, 2·min(1, d_end / R_end) − 1);
//   then the scenario's features.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/rng.hpp"
#include "envs/driving_reward.hpp"
#include "envs/env.hpp"
#include "envs/road.hpp"
#include "envs/scenario_settings.hpp"
#include "envs/sumo_session.hpp"

namespace rapid {

struct Trace;
struct TraceSnapshot;

RAPID_SUMO_BACKEND_BEGIN

// The scenario's design (geometry, sensing, control limits) plus the settings a config may change.
struct DrivingConfig {
  std::string scenario;            // name; also the folder and file stem under network_dir()
  std::vector<std::string> edges;  // the road's edges (first one anchors the progress coordinate)
  std::string ego_route;           // route id (in the scenario's .rou.xml) the ego drives
  double step_length = 0.1;        // s
  // Up to this many extra SUMO steps of traffic before the ego enters, on top of the profile's
  // traffic_warmup. (Not the run config's warmup_steps: random-action decisions before learning.)
  int traffic_warmup_jitter = 50;
  double sensing_range = 100.0;    // R (m): vehicles farther away read as missing
  double lane_end_range = 200.0;   // R_end (m) of the "lane continues ahead" entries
  double speed_norm = 35.0;        // v_norm (m/s): also the ego's top speed under agent control
  double rel_speed_norm = 15.0;    // m/s
  double max_accel = 4.0;          // m/s² at |a0| = 1
  int extra_features = 0;          // scenario features appended to the observation
  ScenarioSettings settings;       // horizon, control rate, traffic, reward variant, …
};

class DrivingEnv : public Env {
 public:
  static constexpr int kCommonObs = 17;
  static constexpr const char* kEgo = "ego";

  explicit DrivingEnv(DrivingConfig config);
  ~DrivingEnv() override;

  std::string name() const override { return config_.scenario; }
  int obs_dim() const override { return kCommonObs + config_.extra_features; }
  int act_dim() const override { return 2; }
  int horizon() const override { return config_.settings.horizon; }
  void reset(std::uint64_t seed, VecRef obs) override;
  StepResult step(const ConstVecRef& action, VecRef obs) override;
  void set_builtin_driver(bool on) override { builtin_ = on; }
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
  const DrivingConfig& config() const { return config_; }
  const driving::RewardWeights& reward_weights() const { return weights_; }

 protected:
  // Puts scenario vehicles on the road before the warm-up (simulation time 0).
  virtual void populate(Rng&) {}
  // Lane index on the first edge of the ego's route where the ego enters.
  virtual int ego_depart_lane(Rng& rng) = 0;
  // Called once per decision after the state is read (e.g. scripted manoeuvres of others).
  virtual void after_observe() {}
  // Writes config().extra_features values in [-1, 1].
  virtual void write_features(float*) const {}

  bool builtin_driver() const { return builtin_; }
  // Distance along the road from the ego to `progress` (negative once passed).
  double distance_to(double progress) const { return progress - ego_.progress; }

 private:
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

  DrivingConfig config_;
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

// lane-drop, cut-in or merge in this backend's build (throws std::invalid_argument for any other
// name or bad settings).
std::unique_ptr<DrivingEnv> make_driving_env(const std::string& name, const ScenarioSettings& settings);

RAPID_SUMO_BACKEND_END
}  // namespace rapid
