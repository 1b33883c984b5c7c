// `rapid simulate-decide SWEEP_DIR`: how `rapid sweep --decide` would fare against fixed designs
// on this sweep's own per-seed results (report/decide_simulation.hpp, docs/decisions.md
// §Simulation): runs spent and verdicts reached, written to SWEEP_DIR/decide-simulation.md.
#include <iostream>

#include "core/atomic_file.hpp"
#include "experiments/cli/checks.hpp"
#include "experiments/cli/commands.hpp"
#include "experiments/cli/errors.hpp"
#include "experiments/report/decide_simulation.hpp"
#include "experiments/report/summarize.hpp"
#include "experiments/sweep/state.hpp"

namespace rapid {

namespace {

struct SimulateOptions {
  std::string sweep;
  int experiments = 2000;
  std::uint64_t seed = 1;
  DecideSettings plan;
};

int simulate_decide_command(const SimulateOptions& o) {
  if (o.plan.max_seeds <= 0 || o.plan.block <= 0) throw UsageError("--max-seeds and --block: must be positive");
  SummaryOptions summary_options;
  summary_options.dataset_stats = false;
  const Summary observed = check_option("SWEEP_DIR", [&] { return build_summary(o.sweep, summary_options); });
  if (!observed.decisions)
    throw UsageError("SWEEP_DIR: the sweep's profile '" + observed.grid.profile + "' has no decision rule (decisions.json)");
  // The grid's own seeds: those it started with if --decide has added some since.
  int initial = static_cast<int>(observed.grid.seeds.size());
  if (const auto plan = read_json_file(std::filesystem::path(o.sweep) / sweep_files::kDecide);
      plan && plan->contains("initial_seeds") && (*plan)["initial_seeds"].is_array())
    initial = static_cast<int>((*plan)["initial_seeds"].size());
  if (const std::string problem = decide_plan_problem(initial, o.plan); !problem.empty()) throw UsageError(problem);
  const DecideSimulation sim = simulate_decide(observed, initial, o.plan, o.experiments, o.seed);
  const std::string md = decide_simulation_markdown(sim, observed.grid.name);
  write_file_atomic((std::filesystem::path(o.sweep) / "decide-simulation.md").string(), md);
  std::cout << md;
  return kExitOk;
}

}  // namespace

Command add_simulate_decide_command(CLI::App& parent) {
  auto o = std::make_shared<SimulateOptions>();
  CLI::App* sub = parent.add_subcommand(
      "simulate-decide", "Simulate --decide against fixed designs from a sweep's own per-seed results (runs and verdicts)");
  sub->add_option("sweep", o->sweep, "a sweep folder with its records")->required();
  sub->add_option("--experiments", o->experiments, "simulated experiments (default 2000)")->check(CLI::Range(1, 1000000));
  sub->add_option("--seed", o->seed, "the simulation's random seed (default 1)")->check(seed_validator());
  sub->add_option("--max-seeds", o->plan.max_seeds, "as for rapid sweep --decide (default 30)")->check(CLI::Range(2, 1000));
  sub->add_option("--block", o->plan.block, "as for rapid sweep --decide (default 5)")->check(CLI::Range(1, 1000));
  sub->add_option("--futility", o->plan.futility, "as for rapid sweep --decide (default 0.1)")->check(CLI::Range(0.0, 0.99));
  return {sub, [o] { return simulate_decide_command(*o); }};
}

}  // namespace rapid
