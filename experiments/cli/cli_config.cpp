#include "experiments/cli/cli_config.hpp"

#include <stdexcept>

#include "experiments/cli/errors.hpp"
#include "experiments/run/run_config.hpp"
#include "experiments/sweep/grid.hpp"

namespace rapid {

void load_grid_scenarios(const std::string& grid_path) {
  if (grid_path.empty()) return;
  try {
    load_grid(grid_path);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
}

nlohmann::json resolve_cli_config(const std::string& scenario, const std::string& profile, const std::string& grid_path,
                                  const nlohmann::json& set_overrides, const std::string& algo) {
  std::string chosen = profile.empty() ? kDefaultProfile : profile;
  nlohmann::json overrides;
  if (!grid_path.empty()) {
    const Grid grid = load_grid(grid_path);
    if (!profile.empty() && profile != grid.profile)
      throw std::invalid_argument("--profile: '" + profile + "' differs from the grid's profile '" + grid.profile + "'");
    chosen = grid.profile;
    overrides = grid_overrides(grid, scenario, algo);
  }
  try {
    check_profile(chosen, scenario);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("--profile: ") + e.what());
  }
  return resolve_config(scenario, chosen, overrides, set_overrides);
}

}  // namespace rapid
