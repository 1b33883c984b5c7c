// `rapid sweep GRID --decide --backend slurm` (docs/cluster.md §Adaptive seeds): the looks of
// cli/sweep_decide.hpp on a cluster. Each submission ends with one small job that waits for its
// arrays (afterany) and runs the next look, `rapid sweep SWEEP --decide-step` (hidden from --help):
// it replays the looks from the records, submits the next block of seeds with another such job
// after it, or, when the looks stop, refreshes the reports. So the whole adaptive sweep runs on the
// cluster with no process left waiting on the login node. A look whose jobs fail stops the chain;
// the same command again resubmits them and carries on.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <ostream>

#include "experiments/cli/sweep_decide.hpp"
#include "experiments/sweep/slurm_backend.hpp"

namespace rapid {

// What the follow-up jobs need to submit the later looks as the user submitted the first: the
// Slurm options and whether to refresh the reports (with animations) when the looks stop. Kept
// in decide.json under "slurm".
struct DecideOnSlurm {
  SlurmOptions slurm;
  bool summary = true;
  bool animations = true;
};
nlohmann::json decide_on_slurm_json(const DecideOnSlurm& settings);

// After a submission of `plan` (empty: nothing needed submitting), from the user's command: with
// arrays, the follow-up that runs the next look; without, the looks themselves, right here, until
// one is submitted. Returns the exit code; `out` says what happened.
int continue_decide_on_slurm(const SweepFolder& folder, const SlurmPlan& plan, const DecideOnSlurm& settings,
                             std::ostream& out);

// The follow-up job's command: `rapid sweep SWEEP --decide-step`. Returns the exit code (0 when
// the looks stopped or the next is submitted, 1 when a look's jobs failed).
int decide_step_command(const std::filesystem::path& sweep_dir, std::ostream& out);

}  // namespace rapid
