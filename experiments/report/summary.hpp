// The summary of a sweep (docs/reports.md), as summarize.hpp reads it from the sweep folder: every
// table cell's per-seed results from the run records, the statistics over seeds, the curves behind
// Figures 2 and 3(b), the prior datasets' statistics behind Figure 3(a), and the claims check.
// Everything the reports, `rapid diff` and scripts/plot need, so none of them reads records on its
// own.
//
// Cells are keyed as the job graph has them: (scenario, dataset, algo, axis point) with an empty
// dataset for ddpg, whose one cell per scenario appears in every dataset row of the table (as in
// the paper); likewise a cell that does not read an axis appears in the row of every value.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "core/hypothesis_tests.hpp"
#include "core/statistics.hpp"
#include "experiments/report/run_provenance.hpp"
#include "experiments/sweep/grid.hpp"

namespace rapid {

inline constexpr const char* kSummarySchema = "rapid.summary/1";

// What became of one seed of a cell. status: ok | failed | diverged | missing (no record yet) |
// stale (its config hash no longer matches the grid) | corrupt (unreadable record).
struct SeedResult {
  std::uint64_t seed = 0;
  std::string status;
  std::optional<double> final_return;  // final.return_mean of an ok record
  int final_episodes = 0;              // its final evaluation's episodes; 0: the last K evaluations' mean
  std::string error;                   // one line for anything but ok
  // Every evaluation of an ok record: (step, return_mean), the x of Figure 2; for runs.csv.
  std::vector<std::pair<double, double>> eval;
  // Its BC-loss log: (step, prior, online), NaN where a loss is null (decided claim C6).
  std::vector<std::tuple<double, double, double>> bc_loss;
  std::optional<double> wall_s;  // what an ok run took, start to end (its record's timing.wall_s)
};

// A curve averaged over the ok seeds at each step; n = how many seeds had a point there.
struct MeanCurve {
  std::vector<double> step, mean, std;
  std::vector<int> n;
  bool empty() const { return step.empty(); }
};

struct CellSummary {
  std::string scenario, dataset, algo;  // dataset empty for ddpg
  AxisPoint axis;                       // the axis values the cell runs at (empty without axes)
  std::vector<SeedResult> seeds;        // one per grid seed, in grid order
  int n_ok = 0;
  int n_expected = 0;
  std::map<std::string, int> statuses;  // status → count
  std::vector<double> finals;           // final returns of the ok seeds
  std::optional<double> mean, std, iqm;
  std::optional<Interval> mean_ci, iqm_ci;
  MeanCurve eval;                       // return_mean over target_step
  MeanCurve bc_prior, bc_online;        // rapid-rl and other prior algorithms; prior empty without one
  MeanCurve q_value;                    // the critic's mean Q over the batch (losses.q_mean)
  MeanCurve temperature;                // a learned entropy temperature α (losses.temperature; rlpd-sac)
  MeanCurve collision_rate;             // share of evaluation episodes ended by a collision (driving)
  // The two forces on the actor at its output (records' "gradients"): the Q term's λ‖∂Q/∂a‖ and
  // the imitation term's ‖2·w·(π(s) − a)‖, on the batch's prior and online halves.
  MeanCurve q_grad_prior, q_grad_online, bc_grad_prior, bc_grad_online;
  std::optional<double> eval_auc;       // area under the mean eval curve / step range
  std::string key() const;              // "merge/initial/rapid-rl", "merge/none/ddpg", "merge/initial/rapid-rl/epsilon=0.3"
  // The cell with `kept` as its seeds (a replay's or a simulation's subset): finals and n_ok follow
  // from them; n_expected and the statistics are the caller's to set.
  void replace_seeds(std::vector<SeedResult> kept);
};

// One row of Table I: a scenario × dataset and the cell index of each algorithm column.
struct TableRow {
  std::string scenario, dataset;
  AxisPoint axis;  // every axis varied in the scenario; a column shows the cell at the part its algorithm reads
  std::vector<std::pair<std::string, std::size_t>> cells;  // (algo, index into Summary::cells)
  std::optional<std::string> best;  // the algorithm with the highest mean (ties: the first column)
};

// The paper's baselines, which the claims compare RAPID-RL with (C1, C5): its other Table I
// columns. An algorithm the paper does not have (rlpd-sac, rapid-rl-return) is a column of our
// tables, and the claims leave it out.
bool is_paper_baseline(const std::string& algo);

// An algorithm RAPID-RL is asked to beat in the probability-of-improvement table: the paper's
// baselines and those it does not have (rlpd-sac, td3-bc), but not RAPID-RL's own variants
// (Algorithm::variant, such as rapid-rl-return), which are asked to beat RAPID-RL instead.
bool is_baseline(const std::string& algo);

// P(algo > baseline) in one row: RAPID-RL against each baseline (is_baseline), and each variant of
// RAPID-RL against RAPID-RL.
struct PoiEntry {
  std::string scenario, dataset, baseline;
  std::string algo;  // RAPID-RL, or a variant of it beside RAPID-RL as the baseline
  std::string point;  // the row's axis point label
  double p = 0.0;
  std::optional<Interval> ci;
  int n_x = 0, n_y = 0;
};

struct AggregateEntry {
  std::string algo;
  double iqm = 0.0;
  Interval ci;
  int n_runs = 0, n_cells = 0;
};

// What an algorithm's ok runs took in one scenario (wall time, start to end, from the records'
// timing.wall_s): the median over all its cells and seeds there, the fastest and the slowest.
struct RunCost {
  std::string scenario, algo;
  double median_s = 0.0, min_s = 0.0, max_s = 0.0;
  int n_runs = 0;
  double total_s = 0.0;  // the runs summed
};

struct DatasetSummary {
  std::string scenario, dataset;
  std::string point;       // the reference point's label ("gamma=0.9"); empty without reference axes
  bool present = false;
  std::string error;       // why it could not be read
  nlohmann::json stats;    // transitions, episodes, return/reward mean/std, reward_histogram
};

struct ClaimResult {
  std::string id;           // C1 … C6
  std::string statement;    // the paper's claim in one line
  std::string definition;   // exactly what is checked
  std::string verdict;      // PASS | FAIL | N/A
  std::string reason;       // one line: the numbers that decided it, or what is missing
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
};

// One line of a sensitivity figure: an algorithm's final return along one axis, the other axes
// held at `others`. An algorithm that does not read the axis has the same cell at every value
// (reads false: drawn flat, for reference).
struct SensitivityLine {
  std::string axis, scenario, dataset, algo;
  AxisPoint others;
  bool reads = true;
  std::vector<nlohmann::json> values;          // the axis values, in the grid's order
  std::vector<std::optional<double>> mean;     // per value: mean final return over the ok seeds
  std::vector<std::optional<Interval>> ci;     // its 95% interval
  std::vector<int> n_ok;
};

struct BootstrapSettings {
  int cell_replicates = 10000;
  int aggregate_replicates = 50000;
  int poi_replicates = 2000;
  std::uint64_t seed = 0x5eed'5a3a'0000'0001ULL;
  double confidence = 0.95;
};

// Decided claims (docs/decisions.md; experiments/report/decisions.hpp computes them).
// A profile's decision rule, experiments/configs/<profile>/decisions.json.
struct DecisionSettings {
  double alpha = 0.05;
  double power = 0.8;
  std::map<std::string, double> delta;  // per scenario, in return units
  std::string delta_rule;               // how δ was chosen, in words
  // Looks of an adaptive (--decide) sweep: each decides at alpha / looks (docs/decisions.md).
  int looks = 1;
  double alpha_per_look() const { return alpha / looks; }
};

enum class ComparisonOutcome { kXBetter, kYBetter, kEquivalent, kUndecided };
const char* outcome_name(ComparisonOutcome o);  // "X better" style text is built by the reports

struct Comparison {
  std::string where;   // "merge / medium", "merge / final+medium, all steps"
  std::string metric;  // "final return", "curve area", "BC loss"
  std::string x, y;    // what is compared (an algorithm or "CoL-prior final+medium", "prior")
  ComparisonOutcome wanted = ComparisonOutcome::kXBetter;  // the outcome the claim needs
  bool paired = false;
  std::optional<double> delta;  // the equivalence margin; none: no equivalence test
  std::vector<double> xs, ys;
  std::vector<std::string> cells;  // the table cells behind xs and ys (CellSummary::key())
  MeanDifference d;
  double p_difference = 0.0, p_equivalence = 0.0;  // NaN where not computed
  ComparisonOutcome outcome = ComparisonOutcome::kUndecided;
  std::optional<int> seeds_needed;  // undecided ones: per side, to resolve δ (or the observed gap)
  // Adaptive seeds (report/decide_looks.hpp): when and why it was frozen ("decided at look 1, 15
  // seeds"; "futile at look 0, 10 seeds: …"); empty: decided on the seeds its cells have now.
  std::string frozen;
  std::string key;  // comparison_key, set when the family is built
};

// A comparison's identity across looks: where, metric, x and y, and "#2" on the second of two
// such (C1 and C2 both compare RAPID-RL with DDPG on final return, for different claims).
std::string comparison_key(const Comparison& c);
// Comparisons decided once (at a look of adaptive seeds), as they were then, by comparison_key.
using FrozenComparisons = std::map<std::string, Comparison>;

struct DecidedClaim {
  std::string id;
  std::string verdict;  // CONFIRMED | REFUTED | UNDECIDED | N/A
  std::string reason;
  std::vector<std::size_t> comparisons;  // indices into Decisions::comparisons
};

struct Decisions {
  DecisionSettings settings;
  int family_size = 0;  // hypotheses under Holm's control
  std::vector<Comparison> comparisons;
  std::vector<DecidedClaim> claims;
};

struct Summary {
  std::filesystem::path sweep_dir;
  Grid grid;
  BootstrapSettings bootstrap;
  std::vector<CellSummary> cells;  // ordered by scenario, dataset, algorithm (table order)
  std::vector<TableRow> rows;
  std::vector<PoiEntry> poi;       // P(rapid-rl > baseline) per row
  std::vector<AggregateEntry> aggregate;  // grids without axes only (it would pool axis values)
  std::vector<RunCost> run_costs;         // per scenario × algorithm with a timed ok run, table order
  std::vector<SensitivityLine> sensitivity;  // grids with axes
  std::map<std::string, double> epsilon;  // per scenario
  std::map<std::string, nlohmann::json> reference;  // per scenario: the reference agent's final result
  std::vector<DatasetSummary> datasets;
  std::vector<ClaimResult> claims;
  std::optional<Decisions> decisions;  // where the profile has a decision rule
  // RAPID-RL against the baselines the paper does not run, a family of its own
  // (decide_published_baselines); where the profile has a decision rule and the grid such a baseline.
  std::optional<Decisions> baseline_decisions;
  // The aggregate claims (a committed pre-registration's for this grid, and the grid's own), decided
  // as a family of their own (report/decisions.hpp, docs/confirmatory.md); absent without any.
  std::optional<Decisions> aggregate_decisions;
  nlohmann::json adaptive_seeds;       // a --decide folder's looks and runs (adaptive_seeds.hpp); else null
  std::vector<std::string> warnings;  // printed by `rapid summarize`
  RunProvenance provenance;           // of the ok records

  const CellSummary* find(const std::string& scenario, const std::string& dataset, const std::string& algo) const;
  // The cell shown in a row's column: the dataset's cell, or the scenario's ddpg cell.
  const CellSummary* column_cell(const TableRow& row, const std::string& algo) const;
};

// summary.json ("rapid.summary/1", see docs/reports.md).
nlohmann::json summary_to_json(const Summary& summary);
// A folder's summary.json as a document of this schema (`rapid paper`, `rapid beside`): throws
// std::invalid_argument naming the file when it is missing, not JSON, of another schema, or has a
// cell without its scenario, algorithm or dataset (null for a method that reads none).
nlohmann::json read_summary_document(const std::filesystem::path& dir);
// The key of one of such a document's cells, as CellSummary::key() spelled it when writing, with
// the axis values in the order of `axes` (the grid's; none for a grid without axes).
std::string summary_cell_key(const nlohmann::json& cell, const std::vector<GridAxis>& axes = {});

}  // namespace rapid
