// lane-drop (docs/scenarios.md): three lanes become two; the inflow exceeds what the two lanes pass, so the
// humans of the ending lane squeeze in and the traffic ahead of the ego is congested. The ego
// enters on a random lane (the ending one included) and must get through without crashing.
#pragma once

#include "envs/driving_env.hpp"

namespace rapid {
RAPID_SUMO_BACKEND_BEGIN

class LaneDropEnv final : public DrivingEnv {
 public:
  explicit LaneDropEnv(const ScenarioSettings& settings);

 protected:
  int ego_depart_lane(Rng& rng) override;
  // [17] distance to the drop: 2·min(1, d / 600 m) − 1 ahead of it, +1 once past it.
  void write_features(float* out) const override;

 private:
  double drop_progress_ = 0.0;
};

RAPID_SUMO_BACKEND_END
}  // namespace rapid
