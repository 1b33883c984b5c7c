// The driving scenarios by name, in this backend's build (envs/sumo_backend.hpp): make_env()
// asks the libsumo build, make_gui_env() the libtraci one.
#include <stdexcept>

#include "envs/cut_in.hpp"
#include "envs/lane_drop.hpp"
#include "envs/merge.hpp"

namespace rapid {
RAPID_SUMO_BACKEND_BEGIN

std::unique_ptr<DrivingEnv> make_driving_env(const std::string& name, const ScenarioSettings& settings) {
  if (name == "lane-drop") return std::make_unique<LaneDropEnv>(settings);
  if (name == "cut-in") return std::make_unique<CutInEnv>(settings);
  if (name == "merge") return std::make_unique<MergeEnv>(settings);
  throw std::invalid_argument("'" + name + "' is not a driving scenario (lane-drop, cut-in, merge)");
}

RAPID_SUMO_BACKEND_END
}  // namespace rapid
