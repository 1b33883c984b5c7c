// The config a `rapid run` or `rapid dataset build` resolves from its options: the profile (from
// --profile, else the grid's, else short), the grid's overrides for the scenario, then --set.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "experiments/run/run_config.hpp"
#include "experiments/sweep/grid.hpp"

namespace rapid {

// Throws std::invalid_argument naming the option that is wrong (an unknown profile, one that
// differs from the grid's, a bad grid or override).
// The grid at `grid_path` (nullopt when none is given), read once per command; reading it makes
// its scenario files known by their names ("scenario_files") to every later check. A bad grid is
// a UsageError saying "grid PATH: FIELD: problem", as every command says it.
std::optional<Grid> load_cli_grid(const std::string& grid_path);

// The config's layers, lowest first: the scenario's in the profile (default_config_layers), the
// grid's overrides ("grid"), --set ("--set"). `algo`: a run's algorithm, whose "algo_config"
// overrides the grid gives it; empty for a dataset build, which reads the scenario's config alone.
std::vector<ConfigLayer> cli_config_layers(const std::string& scenario, const std::string& profile,
                                           const std::optional<Grid>& grid, const nlohmann::json& set_overrides,
                                           const std::string& algo = "");

// Those layers resolved into one config (resolve_config) for a dataset build.
nlohmann::json resolve_cli_config(const std::string& scenario, const std::string& profile,
                                  const std::optional<Grid>& grid, const nlohmann::json& set_overrides);

}  // namespace rapid
