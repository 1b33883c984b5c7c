#include "experiments/cli/cli_config.hpp"

#include <stdexcept>

#include "experiments/cli/errors.hpp"
#include "experiments/run/run_config.hpp"
#include "experiments/sweep/grid.hpp"

namespace rapid {

std::optional<Grid> load_cli_grid(const std::string& grid_path) {
  if (grid_path.empty()) return std::nullopt;
  try {
    return load_grid(grid_path);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
}

std::vector<ConfigLayer> cli_config_layers(const std::string& scenario, const std::string& profile,
                                           const std::optional<Grid>& grid, const nlohmann::json& set_overrides,
                                           const std::string& algo) {
  std::string chosen = profile.empty() ? kDefaultProfile : profile;
  nlohmann::json overrides;
  if (grid) {
    if (!profile.empty() && profile != grid->profile)
      throw std::invalid_argument("--profile: '" + profile + "' differs from the grid's profile '" + grid->profile + "'");
    chosen = grid->profile;
    overrides = grid_overrides(*grid, scenario, algo);
  }
  try {
    check_profile(chosen, scenario);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("--profile: ") + e.what());
  }
  std::vector<ConfigLayer> layers = default_config_layers(scenario, chosen);
  if (overrides.is_object()) layers.push_back({"grid", overrides});
  if (set_overrides.is_object()) layers.push_back({"--set", set_overrides});
  return layers;
}

nlohmann::json resolve_cli_config(const std::string& scenario, const std::string& profile,
                                  const std::optional<Grid>& grid, const nlohmann::json& set_overrides) {
  const nlohmann::json config = merge_layers(cli_config_layers(scenario, profile, grid, set_overrides), scenario);
  run_config_from_json(config, scenario);  // validates the whole
  return config;
}

}  // namespace rapid
