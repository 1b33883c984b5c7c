#include "envs/scenario_hooks.hpp"

#include <stdexcept>

#include "envs/driving_env.hpp"
#include "envs/sumo_api.hpp"

namespace rapid {
RAPID_SUMO_BACKEND_BEGIN

namespace {
using sumo_api::Vehicle;

// Obstacle ids are "obs<k>"; returns k, or -1 for any other vehicle.
int obstacle_index(const std::string& id) {
  if (id.size() < 4 || id.compare(0, 3, "obs") != 0) return -1;
  int k = 0;
  for (std::size_t i = 3; i < id.size(); ++i) {
    if (id[i] < '0' || id[i] > '9') return -1;
    k = 10 * k + (id[i] - '0');
  }
  return k;
}
// Obstacles only change lane when told to, and then even into a tight gap (a real cut-in):
// TraCI requests are refused only if they would overlap a vehicle.
constexpr int kObstacleLaneChangeMode = 256;
constexpr double kCutInDuration = 3.0;  // s the cut-in request stays active
}  // namespace

CutInObstacles::CutInObstacles(int obstacles) {
  for (int k = 0; k < obstacles; ++k) id_.push_back("obs" + std::to_string(k));
  speed_.assign(obstacles, 0.0);
  trigger_gap_.assign(obstacles, 0.0);
  cutter_.assign(obstacles, 0);
  cut_.assign(obstacles, 0);
}

void CutInObstacles::populate(const DrivingEnv& env, Rng& rng) {
  // At time 0, before any human: spread ahead of where the ego will enter, in random lanes.
  double pos = rng.uniform(60.0, 160.0);
  const ScenarioDescriptor& scenario = env.scenario();
  const int lanes = env.road().edge(scenario.ego.depart_edge).lanes;
  const ScenarioSettings& settings = env.settings();
  for (std::size_t k = 0; k < id_.size(); ++k) {
    speed_[k] = rng.uniform(settings.obstacle_speed_min, settings.obstacle_speed_max);
    cutter_[k] = rng.uniform() < 0.6;
    trigger_gap_[k] = rng.uniform(8.0, 25.0);
    cut_[k] = false;
    const int lane = static_cast<int>(rng.index(lanes));
    Vehicle::add(id_[k], scenario.ego.route, kObstacleType, "now", std::to_string(lane), std::to_string(pos),
                 std::to_string(speed_[k]));
    Vehicle::setMaxSpeed(id_[k], speed_[k]);
    Vehicle::setLaneChangeMode(id_[k], kObstacleLaneChangeMode);
    pos += rng.uniform(80.0, 180.0);
  }
  pending_ = -1;
  completed_ = 0;
}

void CutInObstacles::after_observe(const DrivingEnv& env) {
  const DrivingEnv::EgoState& e = env.ego();
  if (pending_ >= 0) {
    if (e.leader[1].present && obstacle_index(e.leader[1].id) == pending_) ++completed_;
    pending_ = -1;
  }
  // A cutter the ego comes up on in the next lane pulls in front of it (left = 0, right = 2).
  for (int side : {0, 2}) {
    const DrivingEnv::Neighbor& n = e.leader[side];
    if (!n.present) continue;
    const int k = obstacle_index(n.id);
    if (k < 0 || k >= static_cast<int>(id_.size()) || !cutter_[k] || cut_[k] || n.gap > trigger_gap_[k] || e.speed <= n.speed) continue;
    Vehicle::changeLane(id_[k], e.lane, kCutInDuration);
    cut_[k] = true;
    pending_ = k;
    break;
  }
}

std::unique_ptr<ScenarioHook> make_scenario_hook(const std::string& name, const ScenarioSettings& settings) {
  if (name.empty()) return nullptr;
  if (name == kCutInObstaclesHook) return std::make_unique<CutInObstacles>(settings.obstacles);
  throw std::invalid_argument("unknown scenario hook '" + name + "'");
}

RAPID_SUMO_BACKEND_END
}  // namespace rapid
