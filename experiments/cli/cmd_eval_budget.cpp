// `rapid eval-budget SWEEP_DIR`: the evaluation budget chosen by its variance (report/eval_budget.hpp,
// docs/performance.md §The evaluation budget): per scenario, the variance components of the final
// return and the curve's area, the costs of training and of an evaluation episode, and the episodes
// that make a cell mean of given precision cheapest. Writes SWEEP_DIR/eval-budget.md (and .json).
#include <iostream>

#include "core/atomic_file.hpp"
#include "experiments/cli/commands.hpp"
#include "experiments/cli/errors.hpp"
#include "experiments/cli/output_folder.hpp"
#include "experiments/report/eval_budget.hpp"
#include "experiments/sweep/state.hpp"

namespace rapid {

namespace {

// Prints the report; writes eval-budget.md and .json only into --out, never into the folder it
// reads unasked (issue #67, as simulate-decide and replay-decide).
int eval_budget_command(const std::string& sweep, const std::string& out, bool out_given) {
  if (out_given) make_output_folder(out, "--out");  // before the work
  const std::vector<EvalRun> runs = check_option("SWEEP_DIR", [&] { return read_eval_runs(sweep); });
  if (runs.empty()) throw UsageError("SWEEP_DIR: " + sweep + " has no ok run records to measure from");
  const std::vector<EvalBudget> budgets = check_option("SWEEP_DIR", [&] { return eval_budgets(runs); });
  const std::string name = open_sweep_folder(sweep).grid.name;
  const std::string md = eval_budget_markdown(budgets, name);
  std::cout << md;
  if (!out_given) return kExitOk;
  const std::filesystem::path dir = out;
  write_file_atomic((dir / "eval-budget.md").string(), md);
  write_file_atomic((dir / "eval-budget.json").string(), eval_budget_json(budgets).dump(1) + "\n");
  std::cout << "wrote " << (dir / "eval-budget.md").string() << " and eval-budget.json\n";
  return kExitOk;
}

}  // namespace

Command add_eval_budget_command(CLI::App& parent) {
  auto sweep = std::make_shared<std::string>();
  auto out = std::make_shared<std::string>();
  CLI::App* sub = parent.add_subcommand(
      "eval-budget", "The evaluation episodes that make a cell mean of given precision cheapest, from a sweep's records");
  sub->add_option("SWEEP_DIR", *sweep, "a sweep folder with its records")->required();
  CLI::Option* out_option = sub->add_option("--out", *out, "also write eval-budget.md and eval-budget.json into this folder");
  return {sub, [sweep, out, out_option] { return eval_budget_command(*sweep, *out, out_option->count() > 0); }};
}

}  // namespace rapid
