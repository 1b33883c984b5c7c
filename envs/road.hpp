// Static geometry of a scenario's network, read once from SUMO: for every edge its lanes, where
// it starts along the road ("progress", metres), how its lane indices line up with the lanes of
// the edges before and after it, and where each lane ends. The observation's "lane continues
// ahead" entries, the distance features and the lane-change bookkeeping all come from here, so a
// decision needs no extra libsumo calls for them.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "envs/sumo_backend.hpp"

namespace rapid {
RAPID_SUMO_BACKEND_BEGIN

class Road {
 public:
  static constexpr double kNoEnd = std::numeric_limits<double>::infinity();

  struct Edge {
    std::string id;
    int lanes = 0;
    double length = 0.0;
    double offset = 0.0;             // progress at the edge's start
    int lane_shift = 0;              // global lane = lane index + lane_shift
    bool exit = false;               // no outgoing connections: the end of the road
    std::vector<double> lane_end;    // progress where each lane ends (kNoEnd: runs to the exit)
  };

  // Reads the network of the running simulation. Offsets and lane shifts are relative to the
  // first edge in `edge_ids`; the edges must form one connected straight road (ramps included).
  static Road from_simulation(const std::vector<std::string>& edge_ids);

  // Index of the edge with this id, or -1 (e.g. "" for a vehicle not on the road).
  int find(const std::string& id) const {
    for (int i = 0; i < static_cast<int>(edges_.size()); ++i)
      if (edges_[i].id == id) return i;
    return -1;
  }
  const Edge& edge(int i) const { return edges_[i]; }
  const Edge& edge(const std::string& id) const;
  int size() const { return static_cast<int>(edges_.size()); }

 private:
  std::vector<Edge> edges_;
};

RAPID_SUMO_BACKEND_END
}  // namespace rapid
