// DrivingEnv's recording (Env::record): what a trace holds, read from SUMO only while recording.
// Kept apart from the decision's code path: with no trace attached, step() and reset() test one
// pointer and call nothing here.
#include <cmath>

#include "envs/driving_env.hpp"
#include "envs/sumo_api.hpp"
#include "envs/trace.hpp"

namespace rapid {
RAPID_SUMO_BACKEND_BEGIN

namespace {
using sumo_api::Junction;
using sumo_api::Lane;
using sumo_api::Simulation;
using sumo_api::Vehicle;

TraceVehicle read_vehicle(const std::string& id) {
  TraceVehicle v;
  v.id = id;
  const libsumo::TraCIPosition p = Vehicle::getPosition(id);
  v.x = p.x;
  v.y = p.y;
  v.angle = Vehicle::getAngle(id);
  v.type = Vehicle::getTypeID(id);
  v.lane = Vehicle::getLaneID(id);
  v.speed = Vehicle::getSpeed(id);
  v.length = Vehicle::getLength(id);
  v.width = Vehicle::getWidth(id);
  return v;
}
}  // namespace

void DrivingEnv::record(Trace* trace) { trace_ = trace; }

void DrivingEnv::record_road() {
  trace_->scenario = scenario_->name;
  trace_->settings = settings_;
  trace_->step_length = scenario_->step_length;
  trace_->sensing_range = scenario_->sensing_range;
  trace_->reward_weights = weights_;
  if (!trace_->road.empty()) return;
  for (const std::string& edge_id : scenario_->road) {
    TraceEdge edge;
    edge.id = edge_id;
    const Road::Edge& e = road_.edge(edge_id);
    for (int l = 0; l < e.lanes; ++l) {
      TraceLane lane;
      lane.id = edge_id + "_" + std::to_string(l);
      lane.index = l;
      lane.width = Lane::getWidth(lane.id);
      lane.length = Lane::getLength(lane.id);
      for (const libsumo::TraCIPosition& p : Lane::getShape(lane.id).value) lane.shape.push_back({p.x, p.y});
      edge.lanes.push_back(std::move(lane));
    }
    trace_->road.push_back(std::move(edge));
  }
  // The scenario's network is its road: every junction belongs to it.
  for (const std::string& id : Junction::getIDList()) {
    TraceJunction junction;
    junction.id = id;
    for (const libsumo::TraCIPosition& p : Junction::getShape(id).value) junction.shape.push_back({p.x, p.y});
    if (junction.shape.size() >= 3) trace_->junctions.push_back(std::move(junction));
  }
}

void DrivingEnv::record_snapshot(TraceSnapshot& s) const {
  s.time = Simulation::getTime();
  s.ego = read_vehicle(kEgo);
  s.vehicles.clear();
  const double range = scenario_->sensing_range;
  for (const std::string& id : Vehicle::getIDList()) {
    if (id == kEgo) continue;
    const libsumo::TraCIPosition p = Vehicle::getPosition(id);
    if (std::hypot(p.x - s.ego.x, p.y - s.ego.y) > range) continue;
    s.vehicles.push_back(read_vehicle(id));
  }
}

void DrivingEnv::record_reset(std::uint64_t seed) {
  record_road();
  TraceEpisode& ep = trace_->episodes.emplace_back();
  ep.index = static_cast<int>(trace_->episodes.size()) - 1;
  ep.env_seed = seed;
  record_snapshot(ep.start);
}

void DrivingEnv::record_decision(const ConstVecRef& action, double speed_before, const StepResult& r,
                                 const driving::RewardTerms& terms) {
  if (trace_->episodes.empty()) return;  // attached mid-episode: nothing to add the decision to
  TraceEpisode& ep = trace_->episodes.back();
  TraceDecision& d = ep.decisions.emplace_back();
  d.t = static_cast<int>(ep.decisions.size()) - 1;
  if (!builtin_) d.action = std::array<float, 2>{action[0], action[1]};
  d.accel = (ego_.speed - speed_before) / (settings_.action_repeat * scenario_->step_length);
  d.reward = r.reward;
  d.terms = terms;
  d.lane_changes = r.info.lane_changes;
  d.lane_change_failed = r.info.lane_change_failed;
  d.collision = r.info.collision;
  d.terminated = r.terminated;
  d.truncated = r.truncated;
  record_snapshot(d.state);
  ep.ret += r.reward;  // in order and in double precision, as every rollout sums its return
  ep.collision = ep.collision || r.info.collision;
}

RAPID_SUMO_BACKEND_END
}  // namespace rapid
