// cut-in (docs/scenarios.md): slow obstacle vehicles drive at constant speeds well below the ego's desired
// speed on a three-lane road among faster humans. Some obstacles are cutters: when the ego comes
// up behind them in the next lane, they change into the ego's lane just ahead of it. The ego must
// brake for the cut-ins and overtake the obstacles to reach its desired speed.
#pragma once

#include <vector>

#include "envs/driving_env.hpp"

namespace rapid {
RAPID_SUMO_BACKEND_BEGIN

class CutInEnv final : public DrivingEnv {
 public:
  explicit CutInEnv(const ScenarioSettings& settings);

  // For tests: the obstacles' constant speeds and how many cut-ins ended with the obstacle as the
  // ego's leader, this episode.
  const std::vector<double>& obstacle_speeds() const { return speed_; }
  int completed_cut_ins() const { return completed_; }

 protected:
  void populate(Rng& rng) override;
  int ego_depart_lane(Rng& rng) override;
  void after_observe() override;

 private:
  std::vector<std::string> id_;  // "obs0", "obs1", …: the number is the index
  std::vector<double> speed_, trigger_gap_;
  std::vector<char> cutter_, cut_;
  int pending_ = -1;  // obstacle commanded to cut in during the last decision
  int completed_ = 0;
};

RAPID_SUMO_BACKEND_END
}  // namespace rapid
