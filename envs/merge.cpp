#include "envs/merge.hpp"

#include <algorithm>

namespace rapid {
RAPID_SUMO_BACKEND_BEGIN

namespace {
DrivingConfig merge_config(const ScenarioSettings& settings) {
  DrivingConfig c;
  c.settings = settings;
  c.scenario = "merge";
  c.edges = {"acc", "up", "ramp", "down"};
  c.ego_route = "onramp";
  c.extra_features = 1;
  return c;
}
}  // namespace

MergeEnv::MergeEnv(const ScenarioSettings& settings) : DrivingEnv(merge_config(settings)) {}

int MergeEnv::ego_depart_lane(Rng&) {
  const Road::Edge& acc = road().edge("acc");
  accel_lane_end_ = acc.lane_end[0];
  feature_range_ = accel_lane_end_ - road().edge("ramp").offset;
  return 0;  // the ramp's only lane
}

void MergeEnv::write_features(float* out) const {
  // The ramp and the acceleration lane are global lane 0; the main road's lanes are 1 and 2.
  const bool merged = ego().global_lane > 0;
  const double d = distance_to(accel_lane_end_);
  out[0] = merged ? 1.0f : static_cast<float>(2.0 * std::clamp(d / feature_range_, 0.0, 1.0) - 1.0);
}

RAPID_SUMO_BACKEND_END
}  // namespace rapid
