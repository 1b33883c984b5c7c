// SWEEP/sweep.json: what the last `rapid sweep` did (when, which jobs it ran, retries, what
// failed). Written at the end and on interruption; the summariser and CI read it, and nothing
// in it decides whether a job is done (the records do).
#pragma once

#include <string>
#include <vector>

#include "experiments/sweep/state.hpp"

namespace rapid {

inline constexpr const char* kSweepManifestSchema = "rapid.sweep/1";

struct JobReport {
  std::string id;
  std::string state;  // ok | failed | diverged | blocked | not_run (interrupted before it finished)
  bool ran = false;   // false: found done and skipped, or never started
  int attempts = 0;
  std::string error;  // one line, for failed, diverged and blocked jobs
};

struct SweepReport {
  std::string backend = "local";
  int workers = 0;
  std::string only;  // the --only text, empty for the whole grid
  bool force = false;
  std::string started, ended;  // UTC ISO 8601
  double wall_s = 0;
  int interrupted_by = 0;  // the signal that stopped the sweep, 0 if none
  std::size_t jobs_in_grid = 0;
  int attempts = 0;  // child processes started
  int retries = 0;   // attempts after a job's first in this sweep
  std::vector<JobReport> jobs;  // every job the sweep needed, in graph order

  bool all_ok() const;
  std::size_t count(const std::string& state) const;
};

// Writes SWEEP/sweep.json atomically.
void write_sweep_manifest(const SweepFolder& folder, const SweepReport& report);

}  // namespace rapid
