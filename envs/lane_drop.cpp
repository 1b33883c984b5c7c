#include "envs/lane_drop.hpp"

#include <algorithm>

namespace rapid {
RAPID_SUMO_BACKEND_BEGIN

namespace {
DrivingConfig lane_drop_config(const ScenarioSettings& settings) {
  DrivingConfig c;
  c.settings = settings;
  c.scenario = "lane-drop";
  c.edges = {"in", "out"};
  c.ego_route = "main";
  c.extra_features = 1;
  return c;
}
constexpr double kFeatureRange = 600.0;
}  // namespace

LaneDropEnv::LaneDropEnv(const ScenarioSettings& settings) : DrivingEnv(lane_drop_config(settings)) {}

int LaneDropEnv::ego_depart_lane(Rng& rng) {
  drop_progress_ = road().edge("out").offset;
  return static_cast<int>(rng.index(road().edge("in").lanes));
}

void LaneDropEnv::write_features(float* out) const {
  const double d = distance_to(drop_progress_);
  out[0] = d <= 0.0 ? 1.0f : static_cast<float>(2.0 * std::min(1.0, d / kFeatureRange) - 1.0);
}

RAPID_SUMO_BACKEND_END
}  // namespace rapid
