#include "envs/trace.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <string_view>

namespace rapid {

namespace {

// The columns of a vehicle row; docs/traces.md and scripts/plot_animate.py name them too.
constexpr const char* kVehicleFields = R"(["id","type","lane","x","y","angle","speed","length","width"])";

class Writer {
 public:
  std::string out;

  void raw(std::string_view s) { out += s; }
  void str(const std::string& s) { out += nlohmann::json(s).dump(); }
  void integer(long long v) { out += std::to_string(v); }
  void uinteger(unsigned long long v) { out += std::to_string(v); }
  void boolean(bool b) { out += b ? "true" : "false"; }
  // A formatted number; "-0" spellings become "0" and a non-finite value null (JSON has none).
  void number_text(double v, std::string_view s) {
    if (!std::isfinite(v)) {
      out += "null";
      return;
    }
    if (s.size() > 1 && s[0] == '-' && s.find_first_not_of("-0.") == std::string_view::npos) s.remove_prefix(1);
    out += s;
  }
  void fixed(double v, int decimals) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
    number_text(v, buf);
  }
  // The shortest spelling (of 6-9 / 15-17 significant digits) that reads back to the same value.
  void exact(float v) {
    char buf[32];
    for (int digits = 6; digits <= 9; ++digits) {
      std::snprintf(buf, sizeof buf, "%.*g", digits, static_cast<double>(v));
      if (std::strtof(buf, nullptr) == v) break;
    }
    number_text(v, buf);
  }
  void exact(double v) {
    char buf[32];
    for (int digits = 15; digits <= 17; ++digits) {
      std::snprintf(buf, sizeof buf, "%.*g", digits, v);
      if (std::strtod(buf, nullptr) == v) break;
    }
    number_text(v, buf);
  }
  void key(const char* k) {
    out += '"';
    out += k;
    out += "\":";
  }
};

void write_vehicle(Writer& w, const TraceVehicle& v) {
  w.raw("[");
  w.str(v.id);
  w.raw(",");
  w.str(v.type);
  w.raw(",");
  w.str(v.lane);
  w.raw(",");
  w.fixed(v.x, 2);
  w.raw(",");
  w.fixed(v.y, 2);
  w.raw(",");
  w.fixed(v.angle, 2);
  w.raw(",");
  w.fixed(v.speed, 3);
  w.raw(",");
  w.fixed(v.length, 2);
  w.raw(",");
  w.fixed(v.width, 2);
  w.raw("]");
}

void write_state(Writer& w, const TraceSnapshot& s) {
  w.key("time");
  w.fixed(s.time, 2);
  w.raw(",");
  w.key("ego");
  write_vehicle(w, s.ego);
  w.raw(",");
  w.key("vehicles");
  w.raw("[");
  for (std::size_t i = 0; i < s.vehicles.size(); ++i) {
    if (i) w.raw(",");
    write_vehicle(w, s.vehicles[i]);
  }
  w.raw("]");
}

void write_points(Writer& w, const std::vector<std::array<double, 2>>& points) {
  w.raw("[");
  for (std::size_t p = 0; p < points.size(); ++p) {
    if (p) w.raw(",");
    w.raw("[");
    w.fixed(points[p][0], 2);
    w.raw(",");
    w.fixed(points[p][1], 2);
    w.raw("]");
  }
  w.raw("]");
}

void write_settings(Writer& w, const ScenarioSettings& s) {
  w.raw("{");
  w.key("network");
  w.str(s.network);
  w.raw(",");
  w.key("action_repeat");
  w.integer(s.action_repeat);
  w.raw(",");
  w.key("horizon");
  w.integer(s.horizon);
  w.raw(",");
  w.key("lane_change_interval");
  w.integer(s.lane_change_interval);
  w.raw(",");
  w.key("traffic_warmup");
  w.integer(s.traffic_warmup);
  w.raw(",");
  w.key("max_depart_delay");
  w.exact(s.max_depart_delay);
  w.raw(",");
  w.key("desired_speed");
  w.exact(s.desired_speed);
  w.raw(",");
  w.key("reward");
  w.str(s.reward);
  w.raw(",");
  w.key("inflow");
  w.exact(s.inflow);
  w.raw(",");
  w.key("ramp_inflow");
  w.exact(s.ramp_inflow);
  w.raw(",");
  w.key("obstacles");
  w.integer(s.obstacles);
  w.raw(",");
  w.key("obstacle_speed_min");
  w.exact(s.obstacle_speed_min);
  w.raw(",");
  w.key("obstacle_speed_max");
  w.exact(s.obstacle_speed_max);
  w.raw("}");
}

void write_decision(Writer& w, const TraceDecision& d) {
  w.raw("{");
  w.key("t");
  w.integer(d.t);
  w.raw(",");
  w.key("action");
  if (d.action) {
    w.raw("[");
    w.exact((*d.action)[0]);
    w.raw(",");
    w.exact((*d.action)[1]);
    w.raw("]");
  } else {
    w.raw("null");
  }
  w.raw(",");
  w.key("accel");
  w.fixed(d.accel, 3);
  w.raw(",");
  w.key("reward");
  w.exact(d.reward);
  w.raw(",");
  w.key("terms");
  w.raw("{");
  w.key("velocity");
  w.exact(d.terms.velocity);
  w.raw(",");
  w.key("gap");
  w.exact(d.terms.gap);
  w.raw(",");
  w.key("follower");
  w.exact(d.terms.follower);
  w.raw(",");
  w.key("failed_lane_change");
  w.exact(d.terms.failed_lane_change);
  w.raw(",");
  w.key("collision");
  w.exact(d.terms.collision);
  w.raw("},");
  w.key("lane_changes");
  w.integer(d.lane_changes);
  w.raw(",");
  w.key("lane_change_failed");
  w.boolean(d.lane_change_failed);
  w.raw(",");
  w.key("collision");
  w.boolean(d.collision);
  w.raw(",");
  w.key("terminated");
  w.boolean(d.terminated);
  w.raw(",");
  w.key("truncated");
  w.boolean(d.truncated);
  w.raw(",");
  write_state(w, d.state);
  w.raw("}");
}

}  // namespace

std::string trace_to_json(const Trace& trace) {
  Writer w;
  w.raw("{\n ");
  w.key("schema");
  w.str(kTraceSchema);
  w.raw(",\n ");
  w.key("scenario");
  w.str(trace.scenario);
  w.raw(",\n ");
  w.key("settings");
  write_settings(w, trace.settings);
  w.raw(",\n ");
  w.key("policy");
  w.str(trace.policy);
  w.raw(",\n ");
  w.key("seed");
  w.uinteger(trace.seed);
  w.raw(",\n ");
  w.key("traffic");
  w.str(trace.traffic);
  w.raw(",\n ");
  w.key("step_length");
  w.exact(trace.step_length);
  w.raw(",\n ");
  w.key("decision_seconds");
  w.exact(trace.decision_seconds());
  w.raw(",\n ");
  w.key("sensing_range");
  w.exact(trace.sensing_range);
  w.raw(",\n ");
  w.key("reward_weights");
  w.raw("{");
  w.key("offset");
  w.exact(trace.reward_weights.offset);
  w.raw(",");
  w.key("gap");
  w.exact(trace.reward_weights.gap);
  w.raw(",");
  w.key("failed_lane_change");
  w.exact(trace.reward_weights.failed_lane_change);
  w.raw(",");
  w.key("collision");
  w.exact(trace.reward_weights.collision);
  w.raw("},\n ");
  w.key("vehicle_fields");
  w.raw(kVehicleFields);
  w.raw(",\n ");
  w.key("road");
  w.raw("[");
  for (std::size_t e = 0; e < trace.road.size(); ++e) {
    const TraceEdge& edge = trace.road[e];
    w.raw(e ? ",\n  {" : "\n  {");
    w.key("id");
    w.str(edge.id);
    w.raw(",");
    w.key("lanes");
    w.raw("[");
    for (std::size_t l = 0; l < edge.lanes.size(); ++l) {
      const TraceLane& lane = edge.lanes[l];
      if (l) w.raw(",");
      w.raw("{");
      w.key("id");
      w.str(lane.id);
      w.raw(",");
      w.key("index");
      w.integer(lane.index);
      w.raw(",");
      w.key("width");
      w.fixed(lane.width, 2);
      w.raw(",");
      w.key("length");
      w.fixed(lane.length, 2);
      w.raw(",");
      w.key("shape");
      write_points(w, lane.shape);
      w.raw("}");
    }
    w.raw("]}");
  }
  w.raw("],\n ");
  w.key("junctions");
  w.raw("[");
  for (std::size_t j = 0; j < trace.junctions.size(); ++j) {
    if (j) w.raw(",");
    w.raw("{");
    w.key("id");
    w.str(trace.junctions[j].id);
    w.raw(",");
    w.key("shape");
    write_points(w, trace.junctions[j].shape);
    w.raw("}");
  }
  w.raw("],\n ");
  w.key("episodes");
  w.raw("[");
  for (std::size_t i = 0; i < trace.episodes.size(); ++i) {
    const TraceEpisode& ep = trace.episodes[i];
    w.raw(i ? ",\n  {" : "\n  {");
    w.key("index");
    w.integer(ep.index);
    w.raw(",");
    w.key("env_seed");
    w.uinteger(ep.env_seed);
    w.raw(",");
    w.key("length");
    w.integer(static_cast<long long>(ep.decisions.size()));
    w.raw(",");
    w.key("return");
    w.exact(ep.ret);
    w.raw(",");
    w.key("collision");
    w.boolean(ep.collision);
    w.raw(",\n   ");
    w.key("start");
    w.raw("{");
    write_state(w, ep.start);
    w.raw("},\n   ");
    w.key("decisions");
    w.raw("[");
    for (std::size_t d = 0; d < ep.decisions.size(); ++d) {
      w.raw(d ? ",\n    " : "\n    ");
      write_decision(w, ep.decisions[d]);
    }
    w.raw("]}");
  }
  w.raw("]\n}\n");
  return std::move(w.out);
}

}  // namespace rapid
