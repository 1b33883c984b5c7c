#include "envs/driving_env.hpp"

#include <stdlib.h>  // mkstemps
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "core/removed_on_stop.hpp"
#include "envs/scenario_hooks.hpp"
#include "envs/sumo_api.hpp"

namespace rapid {
RAPID_SUMO_BACKEND_BEGIN

namespace {
using sumo_api::Simulation;
using sumo_api::Vehicle;

// All vTypes share minGap 2.5 m; libsumo reports leader and follower distances minus it.
constexpr double kMinGap = 2.5;
// Lane-change mode of the agent's ego: no lane changes of its own (bits 0-7 zero); TraCI requests
// are carried out unless they would overlap another vehicle (bits 8-9 = 1).
constexpr int kAgentLaneChangeMode = 256;
// Speed mode 0: the commanded speed is applied without SUMO's safe-speed, acceleration or
// deceleration checks, so the agent can drive into the vehicle ahead.
constexpr int kAgentSpeedMode = 0;
// getNeighbors modes (bit 0 set: right, bit 1 set: leaders).
constexpr int kLeftFollowers = 0, kRightFollowers = 1, kLeftLeaders = 2, kRightLeaders = 3;
enum Side { kLeft = 0, kCurrent = 1, kRight = 2 };
// Stop this far before the road's exit (an ego that reaches it leaves the simulation).
constexpr double kRoadEndMargin = 50.0;

// The roads' speed limit, and the desired speed the ego vType's speedFactor encodes on it
// (envs/networks/vtypes.add.xml).
constexpr double kSpeedLimit = 30.0;
constexpr double kEgoTypeDesiredSpeed = 25.0;

float clip1(double x) { return static_cast<float>(std::clamp(x, -1.0, 1.0)); }

// A Bernoulli flow's probability per second for `veh_per_hour`, spelled the way the route files
// always spelled it (1980 veh/h → "0.55").
std::string per_second(double veh_per_hour) {
  char text[32];
  std::snprintf(text, sizeof text, "%.10g", veh_per_hour / 3600.0);
  return text;
}

// The scenario's routes (its .rou.xml, whose flows say probability="INFLOW" or "RAMP_INFLOW")
// with the configured inflows filled in, written to a temporary file of this process: SUMO reads
// routes from files only.
std::string write_route_file(const std::string& template_path, const ScenarioSettings& settings) {
  std::ifstream in(template_path);
  std::stringstream text;
  text << in.rdbuf();
  std::string xml = text.str();
  for (const auto& [token, value] : {std::pair{std::string("\"INFLOW\""), settings.inflow},
                                     std::pair{std::string("\"RAMP_INFLOW\""), settings.ramp_inflow}})
    for (auto at = xml.find(token); at != std::string::npos; at = xml.find(token, at))
      xml.replace(at, token.size(), std::string("\"").append(per_second(value)).append("\""));
  // A name no one can guess, created by this call alone (O_EXCL, mode 0600): a predictable name
  // in a shared /tmp let another user's symlink there redirect the write (issue #67).
  // (Strings built by append: GCC 12 warns falsely, -Wrestrict, on "literal" + string here.)
  const std::string tail = std::string("-").append(std::filesystem::path(template_path).filename().string());
  std::string path = (std::filesystem::temp_directory_path() / std::string("rapid-XXXXXX").append(tail)).string();
  const int fd = ::mkstemps(path.data(), static_cast<int>(tail.size()));
  if (fd < 0) throw std::runtime_error("cannot create a route file in " + std::filesystem::temp_directory_path().string() +
                                       ": " + std::strerror(errno));
  std::size_t written = 0;
  while (written < xml.size()) {
    const ssize_t n = ::write(fd, xml.data() + written, xml.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    written += static_cast<std::size_t>(n);
  }
  const bool closed = ::close(fd) == 0;
  if (written != xml.size() || !closed) {
    std::filesystem::remove(path);
    throw std::runtime_error("cannot write the route file " + path);
  }
  return path;
}
}  // namespace

DrivingEnv::DrivingEnv(std::shared_ptr<const ScenarioDescriptor> scenario, const ScenarioSettings& settings)
    : scenario_(std::move(scenario)), settings_(settings) {
  validate_scenario_settings(*scenario_, settings_);
  weights_ = scenario_reward_weights(*scenario_, settings_.reward);
  hook_ = make_scenario_hook(scenario_->hook, settings_);
  session_config_.step_length = scenario_->step_length;
}

DrivingEnv::~DrivingEnv() {
  if (route_file_.empty()) return;
  forget_on_stop(route_file_);
  std::error_code ignored;  // a destructor does not throw: a file already gone is what it wants
  std::filesystem::remove(route_file_, ignored);
}

void DrivingEnv::reset(std::uint64_t seed, VecRef obs) {
  const std::string& s = scenario_->name;
  const ScenarioSettings& settings = settings_;
  const NetworkFiles& network = scenario_->networks.at(settings.network);
  session_config_.net_file = network.net;
  if (route_file_.empty()) {
    route_file_ = write_route_file(network.routes, settings);
    remove_on_stop(route_file_);  // Ctrl-C runs no destructor (issue #67)
  }
  session_config_.route_files = {route_file_};
  session_config_.max_depart_delay = settings.max_depart_delay;
  session_config_.additional_files = scenario_->additional_files;
  session_config_.seed = seed;
  session_.start(session_config_);
  // The scenario's own draws (entry lane, obstacles, warm-up length) use a stream apart from
  // SUMO's: same seed, same episode.
  Rng rng(splitmix64(seed ^ 0x5ce7a410'0000'0000ULL));
  try {
    if (!road_read_) {
      road_ = Road::from_simulation(scenario_->road);
      resolve_features();
      road_read_ = true;
    }
    if (hook_) hook_->populate(*this, rng);
    const int warmup = settings.traffic_warmup + static_cast<int>(rng.index(scenario_->traffic_warmup_jitter + 1));
    for (int i = 0; i < warmup; ++i) Simulation::step();
    const int lane = ego_depart_lane(rng);
    Vehicle::add(kEgo, scenario_->ego.route, scenario_->ego.type, "now", std::to_string(lane), "base", "max");
    // The ego enters as soon as its lane's entry has room.
    for (int i = 0; Vehicle::getRoadID(kEgo).empty(); ++i) {
      if (i == 2000) throw std::runtime_error("the ego found no room to enter within 200 s");
      Simulation::step();
    }
    if (!builtin_) {
      Vehicle::setSpeedMode(kEgo, kAgentSpeedMode);
      Vehicle::setLaneChangeMode(kEgo, kAgentLaneChangeMode);
    } else if (std::abs(settings.desired_speed - kEgoTypeDesiredSpeed) > 1e-9) {
      // SUMO's driver aims at the configured v_des (the ego vType's speedFactor encodes 25 m/s).
      Vehicle::setSpeedFactor(kEgo, settings.desired_speed / kSpeedLimit);
    }
    t_ = 0;
    since_lane_change_ = settings.lane_change_interval;
    read_state();
    if (hook_) hook_->after_observe(*this);
    if (trace_ != nullptr) record_reset(seed);
  } catch (...) {
    rethrow_with_context("scenario '" + s + "': reset(" + std::to_string(seed) + ")");
  }
  episode_over_ = false;
  observe(obs);
}

StepResult DrivingEnv::step(const ConstVecRef& action, VecRef obs) {
  session_.require_active();
  if (episode_over_) throw std::logic_error("scenario '" + scenario_->name + "': step() after the episode ended");
  StepResult r;
  try {
    const Road::Edge& edge = road_.edge(ego_.edge);
    const int lane_before = ego_.global_lane;
    const double speed_before = ego_.speed;
    const double decision_time = settings_.action_repeat * scenario_->step_length;
    bool commanded = false, failed = false;
    double accel = 0.0;
    if (!builtin_) {
      accel = std::clamp(static_cast<double>(action[0]), -1.0, 1.0) * scenario_->max_accel;
      const float threshold = scenario_->lane_change_threshold;
      const int dir = action[1] > threshold ? 1 : (action[1] < -threshold ? -1 : 0);
      if (dir != 0) {
        const int target = ego_.lane + dir;
        if (target < 0 || target >= edge.lanes || since_lane_change_ < settings_.lane_change_interval) {
          failed = true;
        } else {
          // Expires within this decision, so a refused request does not linger into the next.
          Vehicle::changeLane(kEgo, target, decision_time - 0.5 * scenario_->step_length);
          commanded = true;
        }
      }
    }
    bool collision = false;
    const double dt = scenario_->step_length;
    for (int k = 1; k <= settings_.action_repeat && !collision; ++k) {
      // The commanded acceleration, exactly: one setSpeed per SUMO step (slowDown's ramp ends a
      // step late). It holds until the next setSpeed, so the ego never falls back to SUMO's driver.
      if (!builtin_) Vehicle::setSpeed(kEgo, std::clamp(ego_.speed + accel * dt * k, 0.0, scenario_->speed_norm));
      Simulation::step();
      collision = Simulation::getCollidingVehiclesNumber() > 0 && ego_collided();
    }
    read_state();
    if (!collision && !builtin_ && ego_at_dead_end()) collision = true;
    r.info.lane_changes = std::abs(ego_.global_lane - lane_before);
    if (commanded && r.info.lane_changes == 0) failed = true;
    since_lane_change_ = r.info.lane_changes > 0 ? 0 : since_lane_change_ + 1;
    if (hook_) hook_->after_observe(*this);
    ++t_;
    r.info.collision = collision;
    r.info.ego_speed = ego_.speed;
    r.info.lane_change_failed = failed;
    const driving::RewardTerms terms = reward(collision, r.info.lane_changes > 0, failed);
    r.info.reward_terms = terms;
    r.reward = static_cast<float>(terms.total);
    r.terminated = collision;
    const Road::Edge& now = road_.edge(ego_.edge);
    const bool road_end = now.exit && ego_.pos > now.length - kRoadEndMargin;
    r.truncated = !r.terminated && (t_ >= settings_.horizon || road_end);
    if (trace_ != nullptr) record_decision(action, speed_before, r, terms);
  } catch (...) {
    rethrow_with_context("scenario '" + scenario_->name + "': step " + std::to_string(t_));
  }
  episode_over_ = r.terminated || r.truncated;
  observe(obs);
  return r;
}

void DrivingEnv::advance_traffic_only(int sumo_steps) {
  session_.require_active();
  episode_over_ = true;
  try {
    for (int i = 0; i < sumo_steps; ++i) Simulation::step();
  } catch (...) {
    rethrow_with_context("scenario '" + scenario_->name + "': advance_traffic_only");
  }
}

void DrivingEnv::read_state() {
  ego_.speed = Vehicle::getSpeed(kEgo);
  road_id_ = Vehicle::getRoadID(kEgo);
  const int e = road_.find(road_id_);
  if (e < 0) throw std::runtime_error("the ego left the road (on '" + road_id_ + "')");
  ego_.edge = e;
  ego_.lane = Vehicle::getLaneIndex(kEgo);
  ego_.pos = Vehicle::getLanePosition(kEgo);
  const Road::Edge& edge = road_.edge(e);
  ego_.global_lane = ego_.lane + edge.lane_shift;
  ego_.progress = edge.offset + ego_.pos;

  const double range = scenario_->sensing_range;
  auto fill = [&](Neighbor& n, const std::string& id, double dist) {
    const double gap = std::max(0.0, dist + kMinGap);
    n.present = !id.empty() && gap <= range;
    if (!n.present) return;
    n.id = id;
    n.gap = gap;
    n.speed = Vehicle::getSpeed(id);
  };
  const auto leader = Vehicle::getLeader(kEgo, range);
  fill(ego_.leader[kCurrent], leader.first, leader.second);
  const auto follower = Vehicle::getFollower(kEgo, range);
  fill(ego_.follower[kCurrent], follower.first, follower.second);
  auto nearest = [&](Neighbor& n, int mode) {
    n.present = false;
    const auto found = Vehicle::getNeighbors(kEgo, mode);
    const std::pair<std::string, double>* best = nullptr;
    for (const auto& p : found)
      if (best == nullptr || p.second < best->second) best = &p;
    if (best != nullptr) fill(n, best->first, best->second);
  };
  // getNeighbors must only be asked about lanes that exist.
  if (ego_.lane + 1 < edge.lanes) {
    nearest(ego_.leader[kLeft], kLeftLeaders);
    nearest(ego_.follower[kLeft], kLeftFollowers);
  } else {
    ego_.leader[kLeft].present = ego_.follower[kLeft].present = false;
  }
  if (ego_.lane > 0) {
    nearest(ego_.leader[kRight], kRightLeaders);
    nearest(ego_.follower[kRight], kRightFollowers);
  } else {
    ego_.leader[kRight].present = ego_.follower[kRight].present = false;
  }
}

bool DrivingEnv::ego_collided() const {
  for (const auto& id : Simulation::getCollidingVehiclesIDList())
    if (id == kEgo) return true;
  return false;
}

bool DrivingEnv::ego_at_dead_end() const {
  // SUMO stops a vehicle that runs out of lane dead at the lane's end; for the agent's ego (which
  // SUMO does not brake) that is driving off the end of the lane: a crash.
  const double end = road_.edge(ego_.edge).lane_end[ego_.lane];
  return end != Road::kNoEnd && end - ego_.progress < 0.01;
}

driving::RewardTerms DrivingEnv::reward(bool collision, bool changed_lane, bool failed_change) const {
  const Neighbor& lead = ego_.leader[kCurrent];
  const Neighbor& follow = ego_.follower[kCurrent];
  driving::RewardInputs in;
  in.speed = ego_.speed;
  in.desired_speed = settings_.desired_speed;
  in.leader = lead.present;
  in.leader_gap = lead.gap;
  in.leader_speed = lead.speed;
  in.follower = follow.present;
  in.follower_gap = follow.gap;
  in.follower_speed = follow.speed;
  in.collision = collision;
  in.changed_lane = changed_lane;
  in.failed_lane_change = failed_change;
  return driving::reward_terms(weights_, idm_, in);
}

void DrivingEnv::observe(VecRef obs) const {
  const double range = scenario_->sensing_range, rel = scenario_->rel_speed_norm;
  const double v = ego_.speed;
  const Road::Edge& edge = road_.edge(ego_.edge);
  obs[0] = clip1(2.0 * v / scenario_->speed_norm - 1.0);
  obs[1] = since_lane_change_ >= settings_.lane_change_interval ? 1.0f : -1.0f;
  float* o = obs.data() + 2;
  for (const int side : scenario_->neighbour_lanes) {
    const Neighbor& lead = ego_.leader[side];
    const Neighbor& follow = ego_.follower[side];
    o[0] = lead.present ? clip1(lead.gap / range) : 1.0f;
    o[1] = lead.present ? clip1((lead.speed - v) / rel) : 1.0f;
    o[2] = follow.present ? clip1(-follow.gap / range) : -1.0f;
    o[3] = follow.present ? clip1((follow.speed - v) / rel) : -1.0f;
    const int lane = ego_.lane + (side == kLeft ? 1 : (side == kRight ? -1 : 0));
    if (lane < 0 || lane >= edge.lanes) {
      o[4] = -1.0f;
    } else {
      const double end = edge.lane_end[lane];
      o[4] = end == Road::kNoEnd ? 1.0f
                                 : clip1(2.0 * std::clamp((end - ego_.progress) / scenario_->lane_end_range, 0.0, 1.0) - 1.0);
    }
    o += 5;
  }
  write_features(obs.data() + features_at());
}

void DrivingEnv::resolve_features() {
  features_.clear();
  for (const FeatureSpec& spec : scenario_->features) {
    const Road::Edge& edge = road_.edge(spec.edge);
    Feature f{.kind = spec.kind};
    if (spec.kind == FeatureSpec::Kind::kDistanceToEdge) {
      f.target = edge.offset;
      f.range = spec.range;
    } else {
      f.target = edge.lane_end[spec.lane];
      if (f.target == Road::kNoEnd)
        throw std::invalid_argument("feature distance_to_lane_end: lane " + std::to_string(spec.lane) + " of edge '" +
                                    spec.edge + "' does not end");
      f.range = spec.range_from.empty() ? spec.range : f.target - road_.edge(spec.range_from).offset;
      f.global_lane = spec.lane + edge.lane_shift;
    }
    features_.push_back(f);
  }
}

int DrivingEnv::ego_depart_lane(Rng& rng) const {
  const int fixed = scenario_->ego.depart_lane;
  return fixed >= 0 ? fixed : static_cast<int>(rng.index(road_.edge(scenario_->ego.depart_edge).lanes));
}

void DrivingEnv::write_features(float* out) const {
  for (const Feature& f : features_) {
    const double d = f.target - ego_.progress;
    if (f.kind == FeatureSpec::Kind::kDistanceToEdge)
      *out++ = d <= 0.0 ? 1.0f : static_cast<float>(2.0 * std::min(1.0, d / f.range) - 1.0);
    else
      *out++ = ego_.global_lane != f.global_lane ? 1.0f : static_cast<float>(2.0 * std::clamp(d / f.range, 0.0, 1.0) - 1.0);
  }
}

RAPID_SUMO_BACKEND_END
}  // namespace rapid
