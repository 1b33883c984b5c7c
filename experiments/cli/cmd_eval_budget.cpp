// `rapid eval-budget SWEEP_DIR`: the evaluation budget chosen by its variance (report/eval_budget.hpp,
// docs/performance.md §The evaluation budget): per scenario, the variance components of the final
// return and the curve's area, the costs of training and of an evaluation episode, and the episodes
// that make a cell mean of given precision cheapest. Writes SWEEP_DIR/eval-budget.md (and .json).
#include <iostream>

#include "core/atomic_file.hpp"
#include "experiments/cli/commands.hpp"
#include "experiments/cli/errors.hpp"
#include "experiments/report/eval_budget.hpp"
#include "experiments/sweep/state.hpp"

namespace rapid {

namespace {

int eval_budget_command(const std::string& sweep) {
  const std::vector<EvalRun> runs = check_option("SWEEP_DIR", [&] { return read_eval_runs(sweep); });
  if (runs.empty()) throw UsageError("SWEEP_DIR: " + sweep + " has no ok run records to measure from");
  const std::vector<EvalBudget> budgets = check_option("SWEEP_DIR", [&] { return eval_budgets(runs); });
  const std::string name = open_sweep_folder(sweep).grid.name;
  const std::string md = eval_budget_markdown(budgets, name);
  const std::filesystem::path dir = sweep;
  write_file_atomic((dir / "eval-budget.md").string(), md);
  write_file_atomic((dir / "eval-budget.json").string(), eval_budget_json(budgets).dump(1) + "\n");
  std::cout << md;
  return kExitOk;
}

}  // namespace

Command add_eval_budget_command(CLI::App& parent) {
  auto sweep = std::make_shared<std::string>();
  CLI::App* sub = parent.add_subcommand(
      "eval-budget", "The evaluation episodes that make a cell mean of given precision cheapest, from a sweep's records");
  sub->add_option("SWEEP_DIR", *sweep, "a sweep folder with its records")->required();
  return {sub, [sweep] { return eval_budget_command(*sweep); }};
}

}  // namespace rapid
