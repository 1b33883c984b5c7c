// One attempt at one job of a sweep folder, as every backend must do it: prepare the job's folder
// and log before the process starts, judge the attempt from its exit status and the files it left,
// and write the outcome note when the job is settled. The local pool (local_backend.cpp) and a
// cluster array task (slurm_task.cpp) both go through here, so `rapid status` and resume read
// the same files whichever backend ran a job.
#pragma once

#include <string>

#include "experiments/sweep/state.hpp"

namespace rapid {

// Creates the job folder, drops a stale progress file (it would mislead `rapid status`) and
// appends the attempt's header line with its command to the job's log.txt.
void begin_attempt(const SweepFolder& folder, const SweepJob& job, int attempt);

// A killed job leaves its last progress.json behind; it no longer describes a running job.
void discard_progress(const SweepFolder& folder, const SweepJob& job);

struct AttemptVerdict {
  std::string state;       // ok | failed | diverged
  bool retryable = false;  // worth another attempt (a crash or kill, not bad usage or divergence)
  std::string error;       // one line; empty when ok
};

// Judges an attempt that ended by itself (the caller handles attempts it stopped on purpose).
// `expected_hash` is the config hash a cell's record must carry (unused for other jobs).
AttemptVerdict judge_attempt(const SweepFolder& folder, const SweepJob& job, const std::string& expected_hash,
                             int exit_code, int signal);

// The attempts a job gets within one sweep: the first one and the grid's max_retries.
int max_attempts(const SweepFolder& folder);

// Whether the failed attempt number `attempt` is worth another one: it failed in a way that
// may not repeat (a crash or a kill, not bad usage or divergence) and attempts are left.
bool worth_retrying(const SweepFolder& folder, const AttemptVerdict& verdict, int attempt);

// Writes the job's outcome.json once it is settled: ok (for the dataset stage, noting the grid
// inputs it ran for), or failed/diverged with its last exit status and error.
void record_outcome(const SweepFolder& folder, const SweepJob& job, const AttemptVerdict& verdict, int attempts,
                    int exit_code, int signal);

}  // namespace rapid
