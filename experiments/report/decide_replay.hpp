// The looks of adaptive seeds replayed on a folder's records (report/decide_looks.hpp's rule): at
// each look every cell holds the seeds it had then, the grid's own and the blocks it was given, in
// seed order. `rapid summarize` decides a --decide folder with it, `rapid sweep --decide` advances
// with it, and a committed folder's records can be replayed under another rule.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "experiments/report/decide_looks.hpp"
#include "experiments/report/report_folder.hpp"
#include "experiments/report/summary.hpp"

namespace rapid {

// The settings a decide.json plan was run with: block, max_seeds, and its rule ("rule": absent in
// folders made before issue #42, which therefore replay as "redecide"). Throws
// std::invalid_argument naming the field when one is malformed.
DecideSettings decide_settings_of(const nlohmann::json& plan);

// `full` (every record of the folder) with each cell holding its first `seeds_of` seeds of the
// sequence `initial` then `initial`'s largest + 1, + 2, …; nullopt when one of those is not an ok
// record of the cell.
std::optional<Summary> cells_at(const Summary& full, const std::vector<std::uint64_t>& initial,
                                const std::map<std::string, int>& seeds_of);

// The looks on `full`'s records, decided with `decision` at α / K. Under "redecide" each look
// decides on every record up to its block, as that rule always did.
LookReplay replay_folder_looks(const Summary& full, const std::vector<std::uint64_t>& initial,
                               const DecideSettings& settings, DecisionSettings decision);

// The cells of a committed reports folder (summary.json's per-seed finals, runs.csv's per-seed
// curves; report_folder.hpp) as a Summary the looks can be replayed on. Per-seed BC losses are not
// in such a folder: C6's comparisons have no values there.
Summary summary_of_reports(const ReportFolder& folder);

// A folder's per-seed results, for replaying or simulating its looks: its records when it has them
// (jobs/), else its committed reports (summary_of_reports). Throws std::invalid_argument.
Summary folder_results(const std::filesystem::path& dir);

// A folder's looks replayed under both rules (`rapid replay-decide`): what each spent and decided.
struct RuleReplay {
  DecideSettings settings;
  LookReplay replay;
  long runs = 0;  // seeds given, summed over the cells (the grid's own included)
  std::map<std::string, long> runs_by_scenario;  // the same, per scenario
};

// What a run of a scenario costs, measured in another sweep of the same protocol (`--run-times
// SWEEP`, from its records through report/eval_budget.hpp): at the protocol's evaluation, and how
// many times more precision a core-second buys at the evaluation budget's recommendation (the
// smaller of the final return's and the curve area's gain, so both keep their precision).
struct ScenarioRunCost {
  double run_s = 0;            // per run, at the protocol's evaluation
  double recommended_s = 0;    // per run, at the recommendation (fewer episodes: less precise runs)
  double precision_gain = 1;   // run_s·variance now ÷ recommended_s·variance there, ≥ 0
};

// Core-hours of `runs` (per scenario) at the protocol's evaluation, and with the evaluation budget at
// equal precision (each run's cost ÷ its precision gain: more, cheaper runs for the same variance of
// a cell mean). Throws std::invalid_argument naming a scenario `costs` lacks.
struct PricedRuns {
  double hours = 0, hours_with_eval_budget = 0;
};
PricedRuns price_runs(const std::map<std::string, long>& runs, const std::map<std::string, ScenarioRunCost>& costs);
struct DecideReplayReport {
  std::string name;       // the grid's
  bool from_records = false;  // false: from a committed reports folder (no BC losses)
  int initial_seeds = 0, cells = 0;
  double seconds_per_run = 0;  // the folder's mean run time (summary provenance), for core-hours
  std::map<std::string, long> fixed_runs_by_scenario;  // the fixed design's: cells × max seeds
  std::string run_times_from;  // the sweep `costs` were measured in; empty: none given
  std::map<std::string, ScenarioRunCost> costs;
  nlohmann::json published_looks;  // decide.json's looks as the folder's own run made them
  RuleReplay redecide, freeze;
  // The comparisons freeze froze as futile that all the folder's seeds (up to the maximum) decide at
  // the looks' level α/K: the decisions futility would have lost (issue #66), one line each.
  std::vector<std::string> lost_to_futility;
  bool fixed_seed_folder = false;  // a folder run on fixed seeds, replayed as if its first were look 0
};

// The comparisons `replay` froze as futile that `all` (the folder decided on all its seeds, at the
// looks' level) decides, as "where, metric, x vs y: outcome (futile at …)".
std::vector<std::string> decisions_lost_to_futility(const LookReplay& replay, const Decisions& all);

// decide-replay.md: the two rules' looks, runs and verdicts side by side, and the folder's own.
std::string decide_replay_markdown(const DecideReplayReport& r);

}  // namespace rapid
