// What a scenario needs that its descriptor cannot say: a named C++ hook (docs/scenarios.md
// §Hooks). A descriptor names at most one ("hook": "cut-in-obstacles"); the env calls it at the
// two points where a task acts on the road itself.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/rng.hpp"
#include "envs/scenario_settings.hpp"
#include "envs/sumo_backend.hpp"

namespace rapid {
RAPID_SUMO_BACKEND_BEGIN

class DrivingEnv;

class ScenarioHook {
 public:
  virtual ~ScenarioHook() = default;
  // At simulation time 0 of every episode, before the traffic warm-up (the road is read).
  virtual void populate(const DrivingEnv&, Rng&) {}
  // Once per decision, after the env has read the ego's state (and once after the ego entered).
  virtual void after_observe(const DrivingEnv&) {}
};

// cut-in-obstacles: slow obstacle vehicles (the `obstacles` settings) spread along the ego's route
// ahead of where it enters, in random lanes, at constant speeds. Some are cutters: when the ego
// comes up behind one in the next lane, faster than it, the obstacle changes into the ego's lane
// just ahead of it.
class CutInObstacles final : public ScenarioHook {
 public:
  explicit CutInObstacles(int obstacles);
  void populate(const DrivingEnv& env, Rng& rng) override;
  void after_observe(const DrivingEnv& env) override;

  // This episode's constant obstacle speeds, and how many cut-ins ended with the obstacle as the
  // ego's leader.
  const std::vector<double>& obstacle_speeds() const { return speed_; }
  int completed_cut_ins() const { return completed_; }

 private:
  std::vector<std::string> id_;  // "obs0", "obs1", …: the number is the index
  std::vector<double> speed_, trigger_gap_;
  std::vector<char> cutter_, cut_;
  int pending_ = -1;  // obstacle commanded to cut in during the last decision
  int completed_ = 0;
};

// The hook a descriptor names (one of scenario_hook_names()); nullptr for "".
std::unique_ptr<ScenarioHook> make_scenario_hook(const std::string& name, const ScenarioSettings& settings);

RAPID_SUMO_BACKEND_END
}  // namespace rapid
