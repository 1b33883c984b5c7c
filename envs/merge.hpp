// merge (docs/scenarios.md): the ego always enters on the on-ramp, which becomes an acceleration lane
// beside a dense two-lane main road and ends 277 m later. The ego must find a gap and merge
// before the lane ends (running off its end is a crash), then drive on.
#pragma once

#include "envs/driving_env.hpp"

namespace rapid {
RAPID_SUMO_BACKEND_BEGIN

class MergeEnv final : public DrivingEnv {
 public:
  explicit MergeEnv(const ScenarioSettings& settings);

 protected:
  int ego_depart_lane(Rng& rng) override;
  // [17] distance to the end of the acceleration lane while on the ramp or acceleration lane:
  // 2·min(1, d / (ramp + acceleration lane)) − 1; +1 once merged.
  void write_features(float* out) const override;

 private:
  double accel_lane_end_ = 0.0, feature_range_ = 1.0;
};

RAPID_SUMO_BACKEND_END
}  // namespace rapid
