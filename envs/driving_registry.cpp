// The driving scenarios by name, in this backend's build (envs/sumo_backend.hpp): make_env()
// asks the libsumo build, make_gui_env() the libtraci one.
#include "envs/driving_env.hpp"

namespace rapid {
RAPID_SUMO_BACKEND_BEGIN

std::unique_ptr<DrivingEnv> make_driving_env(const std::string& name, const ScenarioSettings& settings) {
  return std::make_unique<DrivingEnv>(scenario_descriptor(name), settings);
}

RAPID_SUMO_BACKEND_END
}  // namespace rapid
