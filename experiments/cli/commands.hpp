// Each `rapid` subcommand lives in its own cmd_<name>.cpp and registers itself here: it adds its
// CLI11 subcommand (options bound to state captured by `run`) and returns both.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <functional>

namespace rapid {

struct Command {
  CLI::App* app;             // the subcommand; `run` is called when it was given
  std::function<int()> run;  // returns the process exit code; may throw (see errors.hpp)
};

Command add_rollout_command(CLI::App& parent);
Command add_dataset_command(CLI::App& parent);
Command add_run_command(CLI::App& parent);
Command add_sweep_command(CLI::App& parent);
Command add_status_command(CLI::App& parent);
Command add_summarize_command(CLI::App& parent);
Command add_diff_command(CLI::App& parent);
Command add_bench_command(CLI::App& parent);
Command add_budget_command(CLI::App& parent);
Command add_recheck_command(CLI::App& parent);
Command add_simulate_decide_command(CLI::App& parent);
Command add_replay_decide_command(CLI::App& parent);
Command add_eval_budget_command(CLI::App& parent);
Command add_paper_command(CLI::App& parent);
Command add_beside_command(CLI::App& parent);
Command add_tune_command(CLI::App& parent);
Command add_rerun_command(CLI::App& parent);

// `rapid sweep` of a parsed grid into `out` on local processes (`jobs` 0: one per core), starting
// from `reuse_from`'s references and datasets where it has them for this grid (empty: none), its
// reports refreshed at the end. Returns the exit code; throws UsageError as `rapid sweep` does.
struct Grid;
int sweep_grid(const Grid& grid, const std::string& out, const std::string& reuse_from, int jobs);

// The same for the cells `selection` picks (with the jobs they depend on), on `backend` (local or
// slurm: submitted, not waited for), without refreshing the reports: `rapid tune`'s trials.
struct Selection;
int sweep_selection(const Grid& grid, const std::string& out, const Selection& selection, const std::string& reuse_from,
                    int jobs, const std::string& backend);

// `rapid summarize SWEEP_DIR [--out DIR]`, also run by `rapid sweep` when it ends: the reports
// (with `plots` the figures, with `animations` too the best and worst cells' animations) into
// DIR, default the sweep folder. Returns the exit code. With `force` an --out folder that holds
// other files is written into anyway.
int summarize_sweep(const std::string& sweep_dir, const std::string& out_dir, bool plots, bool animations,
                    bool force = false);

}  // namespace rapid
