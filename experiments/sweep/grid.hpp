// A sweep's grid file (docs/sweeps.md §Grid files): which table cells to run (scenarios × datasets × algorithms ×
// seeds), the config overrides they share, and how the reference agents behind the prior datasets
// are trained. Loading validates everything strictly, so a typo fails before anything is written.
//
// Schema (JSON object; every key not listed is an error):
//   "name"            string of [A-Za-z0-9._-], at most 100 characters: the default sweep folder is results/<name>/
//   "description"     optional string
//   "scenarios"       non-empty array of scenario names (env_names() or a name of "scenario_files"), no duplicates
//   "scenario_files"  optional object: name → path of a scenario file (relative to the grid file's
//                     folder; docs/scenarios.md §Scenario files), its descriptor's name that name
//   "datasets"        non-empty array of initial|medium|final|final+medium, no duplicates
//   "algos"           non-empty array of algorithm names (algo_names()), no duplicates
//   "seeds"           non-empty array of non-negative integers, no duplicates
//   "config"          optional object: config-key overrides for every scenario
//   "scenario_config" optional object: scenario → overrides applied after "config"
//   "reference"       optional object {"seed": 1000, "transitions": 20000, "noise_std": 0.1}:
//                     the reference DDPG agent's seed (not one of "seeds"), the transitions
//                     collected per dataset and the exploration noise used while collecting
//                     and optionally "steps": L, the reference's own training length (an
//                     integer, or an object scenario → integer; default: the cells' steps)
//   "profile"         optional "short" (default) or "flow": the config files cells start from
//   "axes"            optional object: config key → values the sweep varies it over, as an array
//                     for every scenario or an object scenario → array (a scenario left out keeps
//                     its one value). Jobs run at every combination of the axes they read: a cell
//                     at those its algorithm reads (algos/registry.hpp: ε only for RAPID-RL, …),
//                     the reference and dataset jobs at those of keys no algorithm owns. Applied
//                     after "config" and "scenario_config" (docs/sweeps.md §Axes)
//   "algo_config"     optional object: scenario → algorithm → overrides for that algorithm's cells
//                     only, applied last. The reference agent and the dataset builds never see them,
//                     so a scenario's own keys, an axis key and a key the algorithm does not read are
//                     refused. `rapid tune` puts its candidates and its winners here (docs/tuning.md)
//   "external"        optional object: name → {"command": [program, args…], "keys": {…}, "uses_prior": true,
//                     "reads": [method keys, e.g. "epsilon"]}:
//                     methods outside the harness, each run by its command with `--job JOB.json`
//                     appended (experiments/run/external_run.hpp); named in "algos" like any other.
//                     The runs' hashes cover the command, the script's bytes and "keys"
//                     (docs/sweeps.md §External methods)
//   "max_retries"     optional non-negative integer (default 2): extra attempts per failed job
//   "jobs"            optional positive integer: worker processes when --jobs is not given
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "experiments/run/dataset_build.hpp"  // ReferenceSettings, the grid's "reference" object
#include "experiments/run/external_method.hpp"
#include "experiments/run/run_config.hpp"     // kDefaultProfile
#include "experiments/sweep/aggregate_claim.hpp"
#include "experiments/sweep/claim_spec.hpp"

namespace rapid {

// One entry of "axes": a config key and its values per scenario, as the grid spells them.
struct GridAxis {
  std::string key;
  std::map<std::string, std::vector<nlohmann::json>> values;  // scenario → values; absent: not varied there
};

// One combination of axis values, (key, value) in the grid's axis order; empty without axes.
using AxisPoint = std::vector<std::pair<std::string, nlohmann::json>>;

struct Grid {
  std::string name;
  std::string description;
  std::vector<std::string> scenarios, datasets, algos;
  std::map<std::string, std::string> scenario_files;  // name → absolute path of its descriptor
  std::vector<std::uint64_t> seeds;
  std::string profile = kDefaultProfile;  // the config files the cells start from (run_config.hpp)
  nlohmann::json config = nlohmann::json::object();
  nlohmann::json scenario_config = nlohmann::json::object();
  nlohmann::json algo_config = nlohmann::json::object();  // scenario → algorithm → overrides (cells only)
  ReferenceSettings reference;
  std::map<std::string, long> reference_steps;  // "reference"."steps" by scenario (absent: 0)
  std::vector<GridAxis> axes;  // in key order
  std::vector<ClaimSpec> claims;  // the grid's own, checked after the paper's (claim_spec.hpp)
  std::vector<AggregateClaimSpec> aggregate_claims;  // the grid's own "kind": "aggregate" (aggregate_claim.hpp)
  std::map<std::string, ExternalMethod> external;  // "external": name → its command, script and keys
  int max_retries = 2;
  std::optional<int> jobs;
  // The grid with every default spelled out, as written to SWEEP/grid.json. Kept as parsed (not
  // regenerated from the fields) so numbers keep the exact spelling the user gave them.
  nlohmann::json normalized;
};


// A grid is a page of JSON; anything much larger is a mistake (or /dev/zero).
inline constexpr std::size_t kMaxGridBytes = std::size_t{1} << 20;
inline constexpr std::size_t kMaxGridNameLength = 100;
// Jobs one grid may expand to: 20 times the paper grid (docs/sweeps.md).
inline constexpr std::size_t kMaxGridJobs = 10000;

// Reads and validates a grid file. Throws std::invalid_argument with one line
// "grid PATH: FIELD: problem" (e.g. "grid quick.json: algos[2]: unknown algorithm 'sac'; …").
Grid load_grid(const std::string& path);

// The same validation on an already parsed document; `label` names it in messages.
Grid parse_grid(const nlohmann::json& document, const std::string& label);

// "algo_config"[scenario][algo] of the grid: the overrides of that algorithm's cells in that
// scenario; an empty object when the grid has none (or `algo` is empty). The one reader of the
// key's nesting.
nlohmann::json algo_overrides(const Grid& grid, const std::string& scenario, const std::string& algo);

// The overrides a job of `scenario` gets: "config", then "scenario_config"[scenario] on top, then
// for a cell of `algo` (empty: the reference and dataset jobs) "algo_config"[scenario][algo].
nlohmann::json grid_overrides(const Grid& grid, const std::string& scenario, const std::string& algo = "");

// Whether an algorithm of the grid uses prior data: then each scenario has a reference agent and
// a dataset build.
bool grid_uses_prior(const Grid& grid);

// The reference settings of `scenario`'s dataset build.
ReferenceSettings reference_for(const Grid& grid, const std::string& scenario);

// The resolved config of the grid's cells of `scenario` at `point`: its profile's file, then the
// overrides, then the point's axis values, then `algo`'s "algo_config" (none for an empty algo: the
// config the scenario's reference agent and dataset builds read).
nlohmann::json cell_config(const Grid& grid, const std::string& scenario, const AxisPoint& point = {},
                           const std::string& algo = "");

// The points a job of `scenario` runs at: every combination of the values of the axes that vary
// in that scenario and whose key `reads` accepts, in the grid's order (the last axis fastest).
// One empty point when no such axis exists.
std::vector<AxisPoint> axis_points(const Grid& grid, const std::string& scenario,
                                   const std::function<bool(const std::string& key)>& reads);

// The entries of `point` whose key `reads` accepts: the part of a row's point one job reads.
AxisPoint read_part(const AxisPoint& point, const std::function<bool(const std::string& key)>& reads);

// Whether the reference agent and dataset jobs read `key`: every key no algorithm owns.
bool reference_reads(const std::string& key);

// A value as it appears in folder names, ids and `--only`: the JSON number or string as the grid
// spells it ("-0.15", "flow"), a list joined by 'x' ("256x256").
std::string axis_value_label(const nlohmann::json& value);

// "epsilon=0.3,lambda_bc=10"; empty for the empty point.
std::string point_label(const AxisPoint& point);

// The `--set key=value` arguments that put a job at `point`.
std::vector<std::string> point_arguments(const AxisPoint& point);

// Human-readable differences between two normalized grids, one per changed leaf, e.g.
// "config.steps: 1500 → 2000" or "seeds: [0,1] → [0,1,2]". Empty when they are equal.
std::vector<std::string> grid_differences(const nlohmann::json& before, const nlohmann::json& after);

}  // namespace rapid
