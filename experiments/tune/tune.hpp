// `rapid tune GRID --space SPACE` (docs/tuning.md): for each (scenario, algorithm) of the grid, a
// successive-halving search over the space's candidates on the space's tuning seeds, every trial
// a cell of an ordinary sweep folder, so tuning resumes, runs on Slurm and keeps every record.
//
// Tuning folder layout:
//   tune.json          the grid and space it was started with (a later run must match them)
//   c<k>/              candidate k's sweep folder: the grid on the tuning seeds, with candidate
//                      k's overrides and the trials' evaluation in its "algo_config"
//   confirm/c<k>/      the same candidate on the confirmation's fresh seeds: a search's winner k
//                      and the defaults (c0) run there when k is not the defaults
//                      (experiments/tune/confirmation.hpp)
//   tuned.json         the winners, every trial's score, the budget spent (when finished)
//   tuned-grid.json    the grid with each winner in its "algo_config", on the grid's own seeds
//   tune.md            the same as a page: winners, default against tuned, sensitivity, cost
#pragma once

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "experiments/sweep/grid.hpp"
#include "experiments/sweep/selection.hpp"
#include "experiments/tune/confirmation.hpp"
#include "experiments/tune/halving.hpp"
#include "experiments/tune/space.hpp"

namespace rapid {

// Every input checked, nothing written. Throws std::invalid_argument with one line: a grid with
// axes, tuning seeds that are also the grid's, seeds too few for the rungs, a candidate that makes
// an invalid config.
struct TunePlan {
  Grid grid;
  SearchSpace space;
  std::vector<Grid> candidates;   // candidate k's grid (its sweep folder c<k>)
  std::vector<Grid> confirming;   // candidate k's grid on the confirmation seeds (confirm/c<k>)
  std::vector<std::uint64_t> confirmation_seeds;  // fresh: 50-99 but the space's and the grid's
  std::map<std::string, double> delta;  // per scenario: the improvement the confirmation is sized for
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
  // unit_scores[k]: candidate k's score on each of its complete units alone, in order.
  std::vector<std::vector<double>> unit_scores;

  // The confirmation, once halving has a winner that is not the defaults: its units (sized from
  // the paired spread of unit_scores), and the winner's and the defaults' unit scores on the fresh
  // seeds so far; `test` once both have all of them.
  struct Confirmation {
    bool needed = false;
    int units = 0;
    double spread = 0.0;  // sd of paired unit differences in the search (NaN: none to size from)
    double delta = 0.0;
    std::vector<double> winner, defaults;
    std::optional<ConfirmationTest> test;
  } confirmation;
  // Halving has its winner and, where one is needed, the confirmation has decided.
  bool finished() const { return state.finished() && (!confirmation.needed || confirmation.test.has_value()); }
  // The candidate whose settings replace the defaults: halving's winner once confirmed, else 0.
  int adopted() const { return confirmation.test && confirmation.test->adopted ? state.winner : 0; }
};
std::vector<TrialScores> replay_tune(const std::filesystem::path& dir, const TunePlan& plan);

// The runs one candidate folder still needs for the searches' current rungs: cells by key and
// the seeds they run (one entry per distinct seed set). `algos`: only their searches (empty: all).
struct TrialJobs {
  int candidate = 0;
  bool confirming = false;  // in confirm/c<k> on the fresh seeds, not in c<k>
  Selection selection;
};
std::vector<TrialJobs> missing_trials(const TunePlan& plan, const std::vector<TrialScores>& searches,
                                      const std::set<std::string>& algos = {});

// The most units a confirmation of `algo` can run: the fresh seeds it has.
int confirmation_max_units(const TunePlan& plan, const std::string& algo);

// The folder of candidate k, and of its confirmation runs.
std::filesystem::path candidate_dir(const std::filesystem::path& dir, int k);
std::filesystem::path confirming_dir(const std::filesystem::path& dir, int k);
// The folder `trials` run in: confirming_dir or candidate_dir.
std::filesystem::path trials_dir(const std::filesystem::path& dir, const TrialJobs& trials);

// tune.json's content: what a later `rapid tune` into the same folder must match (the grid but
// for its algorithms, and the space).
nlohmann::json tune_identity(const TunePlan& plan);

// Writes tuned.json, tuned-grid.json and tune.md once every search has finished.
void write_tune_results(const std::filesystem::path& dir, const TunePlan& plan, const std::vector<TrialScores>& searches);

// The tuned grid: `grid` with each winner's overrides in "algo_config", named <grid>-tuned.
nlohmann::json tuned_grid(const TunePlan& plan, const std::vector<TrialScores>& searches);

}  // namespace rapid
