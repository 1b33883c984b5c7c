// `rapid simulate-decide FOLDER`: how `rapid sweep --decide` would fare against fixed designs
// on a sweep's own per-seed results (report/decide_simulation.hpp, docs/decisions.md
// §Simulation): runs spent, verdicts reached and decisions lost to futility. Reads a sweep folder's
// records, or a committed reports folder's summary.json and runs.csv. Prints the report; writes it
// only where --out says (issue #67: a command that reads a folder does not write into it unasked).
#include <algorithm>
#include <iostream>

#include "core/atomic_file.hpp"
#include "experiments/cli/checks.hpp"
#include "experiments/cli/commands.hpp"
#include "experiments/cli/errors.hpp"
#include "experiments/cli/output_folder.hpp"
#include "experiments/report/decide_replay.hpp"
#include "experiments/report/decide_simulation.hpp"
#include "experiments/report/decisions.hpp"
#include "experiments/report/summarize.hpp"
#include "experiments/sweep/state.hpp"

namespace rapid {

namespace {

namespace fs = std::filesystem;

struct SimulateOptions {
  std::string folder;
  std::string out;
  int experiments = 2000;
  std::uint64_t seed = 1;
  DecideSettings plan;
};

// The folder's cells with their per-seed results (report/decide_replay.hpp's folder_results), decided
// as its summary is: a committed reports folder's have no decisions of their own until decided here.
Summary observed_cells(const fs::path& dir) {
  Summary s = folder_results(dir);
  if (!s.decisions)
    if (const std::optional<DecisionSettings> decision = load_decision_settings(s.grid.profile))
      s.decisions = decide_claims(s, *decision);
  return s;
}

int simulate_decide_command(const SimulateOptions& o) {
  if (o.plan.max_seeds <= 0 || o.plan.block <= 0) throw UsageError("--max-seeds and --block: must be positive");
  const Summary observed = check_option("FOLDER", [&] { return observed_cells(o.folder); });
  if (!observed.decisions)
    throw UsageError("FOLDER: the grid's profile '" + observed.grid.profile + "' has no decision rule (decisions.json)");
  const long cells = std::count_if(observed.cells.begin(), observed.cells.end(), [](const CellSummary& c) { return c.n_ok > 0; });
  if (cells == 0) throw UsageError("FOLDER: " + o.folder + " has no cell with an ok seed to simulate from");
  // The grid's own seeds: those it started with if --decide has added some since.
  int initial = static_cast<int>(observed.grid.seeds.size());
  if (const auto plan = read_json_file(fs::path(o.folder) / sweep_files::kDecide);
      plan && plan->contains("initial_seeds") && (*plan)["initial_seeds"].is_array())
    initial = static_cast<int>((*plan)["initial_seeds"].size());
  if (const std::string problem = decide_plan_problem(initial, o.plan); !problem.empty()) throw UsageError(problem);
  const DecideSimulation sim = simulate_decide(observed, initial, o.plan, o.experiments, o.seed);
  const std::string md = decide_simulation_markdown(sim, observed.grid.name);
  if (!o.out.empty()) write_file_atomic(o.out, md);
  std::cout << md;
  return kExitOk;
}

}  // namespace

Command add_simulate_decide_command(CLI::App& parent) {
  auto o = std::make_shared<SimulateOptions>();
  CLI::App* sub = parent.add_subcommand(
      "simulate-decide", "Simulate --decide against fixed designs from a folder's own per-seed results (runs, verdicts, "
                         "decisions lost to futility)");
  sub->add_option("FOLDER", o->folder, "a sweep folder with its records, or its committed reports folder")->required();
  const CLI::Option* out =
      sub->add_option("--out", o->out, "also write the report to this file (default: print it only)");
  sub->add_option("--experiments", o->experiments, "simulated experiments (default 2000)")->check(CLI::Range(1, 1000000));
  sub->add_option("--seed", o->seed, "the simulation's random seed (default 1)")->check(seed_validator());
  sub->add_option("--max-seeds", o->plan.max_seeds, "as for rapid sweep --decide (default 30)")->check(CLI::Range(2, 1000));
  sub->add_option("--block", o->plan.block, "as for rapid sweep --decide (default 5)")->check(CLI::Range(1, 1000));
  sub->add_option("--futility", o->plan.futility, "as for rapid sweep --decide (default 0.1)")->check(futility_validator());
  return {sub, [o, out] {
            if (out->count() > 0) check_output_file("--out", o->out);
            return simulate_decide_command(*o);
          }};
}

}  // namespace rapid
