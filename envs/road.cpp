#include "envs/road.hpp"

#include <functional>
#include <stdexcept>

#include "envs/sumo_api.hpp"

namespace rapid {
RAPID_SUMO_BACKEND_BEGIN

const Road::Edge& Road::edge(const std::string& id) const {
  const int i = find(id);
  if (i < 0) throw std::runtime_error("road has no edge '" + id + "'");
  return edges_[i];
}

Road Road::from_simulation(const std::vector<std::string>& edge_ids) {
  Road road;
  struct Link { int from_edge, from_lane, to_edge, to_lane; };
  std::vector<Link> links;
  for (const auto& id : edge_ids) {
    Edge e;
    e.id = id;
    e.lanes = sumo_api::Edge::getLaneNumber(id);
    e.length = sumo_api::Lane::getLength(id + "_0");
    road.edges_.push_back(e);
  }
  for (int ei = 0; ei < road.size(); ++ei) {
    Edge& e = road.edges_[ei];
    e.exit = true;
    for (int l = 0; l < e.lanes; ++l)
      for (const auto& c : sumo_api::Lane::getLinks(e.id + "_" + std::to_string(l))) {
        const std::string to_lane = c.approachedLane;
        const auto cut = to_lane.rfind('_');
        const int to = road.find(to_lane.substr(0, cut));
        if (to < 0) throw std::runtime_error("lane '" + to_lane + "' leaves the scenario's road");
        links.push_back({ei, l, to, std::stoi(to_lane.substr(cut + 1))});
        e.exit = false;
      }
  }
  // Offsets and lane shifts by propagation along the connections, from the first edge.
  std::vector<bool> placed(road.size(), false);
  placed[0] = true;
  for (bool changed = true; changed;) {
    changed = false;
    for (const auto& k : links) {
      Edge& a = road.edges_[k.from_edge];
      Edge& b = road.edges_[k.to_edge];
      if (placed[k.from_edge] && !placed[k.to_edge]) {
        b.offset = a.offset + a.length;
        b.lane_shift = a.lane_shift + k.from_lane - k.to_lane;
        placed[k.to_edge] = changed = true;
      } else if (placed[k.to_edge] && !placed[k.from_edge]) {
        a.offset = b.offset - a.length;
        a.lane_shift = b.lane_shift + k.to_lane - k.from_lane;
        placed[k.from_edge] = changed = true;
      }
    }
  }
  for (int i = 0; i < road.size(); ++i)
    if (!placed[i]) throw std::runtime_error("edge '" + road.edges_[i].id + "' is not connected to the road");
  // Where each lane ends: followed through its straight successor; a lane without one ends at its
  // edge's end unless the edge is the road's exit.
  std::function<double(int, int)> lane_end = [&](int ei, int l) -> double {
    for (const auto& k : links)
      if (k.from_edge == ei && k.from_lane == l) return lane_end(k.to_edge, k.to_lane);
    const Edge& e = road.edges_[ei];
    return e.exit ? kNoEnd : e.offset + e.length;
  };
  for (int i = 0; i < road.size(); ++i)
    for (int l = 0; l < road.edges_[i].lanes; ++l) road.edges_[i].lane_end.push_back(lane_end(i, l));
  return road;
}

RAPID_SUMO_BACKEND_END
}  // namespace rapid
