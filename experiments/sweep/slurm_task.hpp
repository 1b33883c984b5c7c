// One task of a cluster job array: `rapid sweep SWEEP --run-job I --job-list LIST` (hidden from
// --help) runs entry I of a task list with the same bookkeeping as the local pool — the attempt
// header and output in the job's log.txt, retries up to the grid's max_retries, outcome.json when
// the job is settled — so `rapid status` and resume cannot tell which backend ran a job.
//
// A task list maps array indices to jobs of the sweep folder. The submitter writes one per array
// (only the jobs still to do), so index I of a resubmission is whatever job is left at position I.
// Jobs are named by id rather than graph index: an id keeps its meaning if the grid gains seeds.
#pragma once

#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "experiments/sweep/state.hpp"

namespace rapid {

struct TaskEntry {
  std::string job;     // SweepJob::id()
  bool force = false;  // run even if the job is done (--force); otherwise a done job is skipped
};

// SWEEP/slurm/<submission>/<stage>.json: {"schema", "stage", "jobs": [{"job", "force"}, …]}.
void write_task_list(const std::filesystem::path& path, const std::string& stage, const std::vector<TaskEntry>& entries);
// Throws std::invalid_argument (one line) if the file is missing or malformed.
std::vector<TaskEntry> read_task_list(const std::filesystem::path& path);

// Runs entry `index` of the list (a path relative to the sweep folder, or absolute). Returns the
// exit code: 0 when the job is ok (or was already done), 1 when it failed, diverged, was stopped
// by the scheduler or could not start because a dependency is not done. Throws
// std::invalid_argument for a bad index, list or job id (a usage error).
int run_sweep_task(const SweepFolder& folder, const std::string& list, std::size_t index, const std::string& binary,
                   std::ostream& out);

}  // namespace rapid
