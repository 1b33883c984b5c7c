// The Slurm backend of `rapid sweep` (docs/cluster.md): instead of running the job graph
// here, submit job arrays and return at once: per scenario, one array per stage — reference
// agent, datasets, the cells that need those datasets — each waiting for the one before with
// --dependency=afterok, and one array of the cells that wait for nothing (DDPG, or prior cells
// whose datasets are already built). Each array task runs one job of the sweep folder by index
// (slurm_task.hpp), so results, resume and `rapid status` work from the folder's files alone: no
// sacct, no scontrol (finished jobs leave it after MinJobAge).
//
// afterok waits for every task of an array: if a scenario's reference task fails, that scenario's
// later arrays are cancelled (--kill-on-invalid-dep=yes) instead of waiting forever, while the
// other scenarios go on; `rapid status` shows the failure and the blocked jobs, and submitting
// again runs exactly what is left.
//
// Files, inside the sweep folder:
//   slurm/<submission>/<array>.json     the task list: array index → job (slurm_task.hpp)
//   slurm/<submission>/<array>.sbatch   the script submitted for that array
//   slurm/<array>_<array id>_<index>.out  each task's own output (the job's output is in its log.txt)
// where <array> is e.g. references-merge, datasets-merge, cells-merge, cells-merge-independent.
//   slurm/submissions.json              every submission: when, which arrays, their job ids
#pragma once

#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "experiments/sweep/selection.hpp"
#include "experiments/sweep/slurm_task.hpp"
#include "experiments/sweep/state.hpp"

namespace rapid {

struct SlurmOptions {
  std::string partition;  // empty: the cluster's default partition
  std::string time;       // empty: the partition's default limit
  int cpus_per_task = 1;  // jobs are single-threaded (docs/design.md §Performance rules)
  int array_parallelism = 32;  // the %K throttle: at most K tasks of an array run at once
  std::vector<std::string> sbatch_args;  // more #SBATCH lines, e.g. --mem=4G, --account=X
  std::string binary;     // the rapid executable the tasks run (must be visible on the nodes)
};

// Thrown when sbatch or squeue fails; the message is one line with their own error.
class SlurmError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct SlurmArray {
  std::string stage;             // references | datasets | cells
  std::string scenario;
  std::string name;              // "<stage>-<scenario>", "-independent" added when needed to tell apart
  std::vector<std::size_t> after;  // the arrays (indices into the plan) this one waits for (afterok)
  std::vector<TaskEntry> tasks;  // array index → job
  std::string list;              // the task list file, relative to the sweep folder
  std::string script;            // the sbatch script file, relative to the sweep folder
  std::string job_id;            // once submitted
};

struct SlurmPlan {
  std::string submission;          // slurm/<UTC time>, the folder of this submission's lists
  std::vector<SlurmArray> arrays;  // the arrays that have work; every array after those it waits for
  std::size_t needed = 0;          // jobs the selection needs
  std::size_t done = 0;            // of which already done (not submitted)
  std::size_t tasks() const;
};

// What to submit: every job the selection needs that is not done (or is forced), plus the jobs
// whose dependencies are submitted — whether they are still done after those rerun can only be
// known then, so their tasks check again and skip if so. Reads the folder, writes nothing.
SlurmPlan plan_slurm_sweep(const SweepFolder& folder, const Selection& selection, bool force);

// The sbatch script of plan.arrays[a]; `after` is the job ids it waits for (afterok), colon-separated,
// or empty.
std::string sbatch_script(const SweepFolder& folder, const SlurmPlan& plan, std::size_t a, const std::string& after,
                          const SlurmOptions& options);

// Writes the task lists and scripts, submits the arrays in order (each afterok on those it waits
// for), records them in slurm/submissions.json and sets each array's job_id. Throws SlurmError
// if sbatch fails; arrays submitted before the failure stay submitted (the message names them).
void submit_slurm_plan(const SweepFolder& folder, SlurmPlan& plan, const SlurmOptions& options);

// After submit_slurm_plan: one more job, in the same submission, that waits for every array of
// `plan` to end whatever their outcome (afterany) and then runs `rapid <arguments>` in the sweep
// folder, e.g. `rapid sweep . --decide-step` for --decide's next look. Its script is
// slurm/<submission>/<name>.sbatch, its output slurm/<name>_<job id>.out; it is recorded in
// submissions.json like an array (so a submission while it is queued is refused). Returns its job
// id. Throws SlurmError if sbatch fails (the arrays stay submitted; the message says so).
std::string submit_slurm_follow_up(const SweepFolder& folder, const SlurmPlan& plan, const std::string& name,
                                   const std::vector<std::string>& arguments, const SlurmOptions& options);

// Job ids of arrays submitted to this folder earlier that squeue still lists (pending or
// running): submitting again while they are queued would run jobs twice. Throws SlurmError if
// squeue cannot be run.
std::vector<std::string> queued_slurm_jobs(const SweepFolder& folder);

// Whether an executable named `program` is in one of PATH's folders (sbatch: a Slurm login node).
bool program_on_path(const std::string& program);

// Rejects sbatch arguments that are not options or that rapid sets itself (--array, --chdir, …).
// Throws std::invalid_argument naming the argument.
void check_sbatch_args(const std::vector<std::string>& args);

}  // namespace rapid
