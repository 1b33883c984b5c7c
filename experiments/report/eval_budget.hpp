// The evaluation budget chosen by its variance (docs/performance.md §The evaluation budget, issue
// #42): from a sweep's records, per scenario, what a run costs in training and per evaluation
// episode, how much of the between-run spread of the final return and of the curve's area the
// evaluation episodes add, and the final evaluation's episodes and the curve's episodes per point
// that make a cell mean of given precision cheapest. `rapid eval-budget SWEEP` prints it.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace rapid {

// What one ok record says about evaluation.
struct EvalRun {
  std::string cell;                     // its cell (CellSummary::key())
  std::vector<double> final_episodes;   // final.episode_returns, in evaluation-seed order
  std::vector<double> curve_steps;      // the evaluations' target steps
  std::vector<double> curve_mean;       // their return_mean
  std::vector<double> curve_std;        // their return_std over the curve's episodes
  double wall_s = 0, eval_s = 0;        // timing: the whole run and its evaluations
  int curve_episodes = 0;               // eval_episodes
  int final_episodes_setting = 0;       // final_eval_episodes
  long eval_every = 0, steps = 0;
};

// A scenario's variance components and costs, and the settings they recommend.
struct EvalBudget {
  std::string scenario;
  int runs = 0, cells = 0;
  int points = 0;                 // evaluations per run (step 0 and the end included)
  int curve_episodes = 0, final_episodes = 0;  // the records' settings
  double train_s = 0;             // per run, outside evaluations
  double episode_s = 0;           // per evaluation episode, its reset included
  double eval_share = 0;          // of a run's time
  // Final return: the between-run variance at k final episodes is between + interaction / k
  // (fitted to the records' first k episodes for every k: every run evaluates the same seeds 0, 1, …,
  // so the first k are exactly what a run with k would have). within: the spread of one run's
  // episodes, which the shared evaluation seeds partly keep out of the between-run variance.
  double between = 0, interaction = 0, within = 0;
  std::vector<std::pair<int, double>> measured;  // (k, between-run variance at k), pooled over cells
  // The curve's area (C5): between-run variance of seeds' areas, and the area's episode noise per
  // episode per point (from the points' return_std: an upper bound, shared seeds not taken out).
  double area_between = 0, area_noise = 0;
  int recommended_final = 0, recommended_curve = 0;  // episodes
  int recommended_final_without_curve = 0;           // a grid with no curve (tuning runs)
  double cost_now = 0, cost_recommended = 0;         // per run, seconds
  // Core-seconds per unit of precision (cost × variance of one run's final return): now / recommended.
  double final_saving = 0, area_saving = 0;
};

// Reads the sweep's ok records. Throws std::invalid_argument (one line) when DIR is not a sweep.
std::vector<EvalRun> read_eval_runs(const std::filesystem::path& sweep_dir);

// The budget per scenario of `runs`, which must share their evaluation settings within a scenario
// (std::invalid_argument otherwise, naming the scenario). Cells with fewer than 3 runs are left out.
std::vector<EvalBudget> eval_budgets(const std::vector<EvalRun>& runs);

// The episodes k (1 ≤ k ≤ max_episodes) that minimise (fixed_s + episode_s·k) · (between + noise/k),
// the cost of a mean of given precision; max_episodes when between ≤ 0.
int cheapest_episodes(double fixed_s, double episode_s, double between, double noise, int max_episodes);

// The report: a table per scenario of the components and the recommendation.
std::string eval_budget_markdown(const std::vector<EvalBudget>& budgets, const std::string& sweep_name);
nlohmann::json eval_budget_json(const std::vector<EvalBudget>& budgets);

}  // namespace rapid
