// `rapid tune GRID --space SPACE` (docs/tuning.md): for each (scenario, algorithm) of the grid, a
// successive-halving search over the space's candidates on the space's tuning seeds, every trial
// a cell of an ordinary sweep folder, so tuning resumes, runs on Slurm and keeps every record.
//
// Tuning folder layout:
//   tune.json          the grid and space it was started with (a later run must match them)
//   c<k>/              candidate k's sweep folder: the grid on the tuning seeds, with candidate
//                      k's overrides and the trials' evaluation in its "algo_config"
//   tuned.json         the winners, every trial's score, the budget spent (when finished)
//   tuned-grid.json    the grid with each winner in its "algo_config", on the grid's own seeds
//   tune.md            the same as a page: winners, default against tuned, sensitivity, cost
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "experiments/sweep/grid.hpp"
#include "experiments/sweep/selection.hpp"
#include "experiments/tune/halving.hpp"
#include "experiments/tune/space.hpp"

namespace rapid {

// Every input checked, nothing written. Throws std::invalid_argument with one line: a grid with
// axes, tuning seeds that are also the grid's, seeds too few for the rungs, a candidate that makes
// an invalid config.
struct TunePlan {
  Grid grid;
  SearchSpace space;
  std::vector<Grid> candidates;  // candidate k's grid (its sweep folder c<k>)
};
TunePlan plan_tune(const Grid& grid, const SearchSpace& space);

// One (scenario, algorithm)'s search as the records of `dir` show it.
struct TrialScores {
  std::string scenario, algo;
  HalvingState state;
  std::vector<nlohmann::json> overrides;  // per candidate
  int runs = 0;                            // finished runs (ok or diverged) among the search's trials
  double wall_s = 0;                       // their training and evaluation time
  // scores_by_units[k][u]: candidate k's score after u units, where every run has finished; a
  // diverged run is a result, the worst one (its return −∞, so its candidate ranks last), not a
  // run to retry: training is deterministic and would diverge again.
  std::vector<std::vector<std::optional<double>>> scores_by_units;
};
std::vector<TrialScores> replay_tune(const std::filesystem::path& dir, const TunePlan& plan);

// The runs one candidate folder still needs for the searches' current rungs: cells by key and
// the seeds they run (one entry per distinct seed set). `algos`: only their searches (empty: all).
struct TrialJobs {
  int candidate = 0;
  Selection selection;
};
std::vector<TrialJobs> missing_trials(const TunePlan& plan, const std::vector<TrialScores>& searches,
                                      const std::set<std::string>& algos = {});

// The folder of candidate k.
std::filesystem::path candidate_dir(const std::filesystem::path& dir, int k);

// tune.json's content: what a later `rapid tune` into the same folder must match (the grid but
// for its algorithms, and the space).
nlohmann::json tune_identity(const TunePlan& plan);

// Writes tuned.json, tuned-grid.json and tune.md once every search has finished.
void write_tune_results(const std::filesystem::path& dir, const TunePlan& plan, const std::vector<TrialScores>& searches);

// The tuned grid: `grid` with each winner's overrides in "algo_config", named <grid>-tuned.
nlohmann::json tuned_grid(const TunePlan& plan, const std::vector<TrialScores>& searches);

}  // namespace rapid
