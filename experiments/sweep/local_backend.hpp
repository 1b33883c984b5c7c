// The local backend: runs a sweep folder's job graph on N worker processes on this machine.
// Jobs start when their dependencies are ok; jobs already done (state.hpp) are skipped
// unless forced; a job whose process fails or dies is retried up to the grid's max_retries, then
// stays failed while independent jobs go on and its dependants are marked blocked. A job that
// outlives the job timeout is stopped (SIGTERM, SIGKILL 10 s later) and counts as a failed
// attempt. SIGINT,
// SIGTERM or SIGHUP stop the children, wait for them and return with `interrupted_by` set.
//
// The caller holds the folder's lock and has written its grid.json (cli/cmd_sweep.cpp); this writes
// job logs, outcome notes and, at the end, SWEEP/sweep.json.
#pragma once

#include <ostream>
#include <string>

#include "experiments/sweep/manifest.hpp"
#include "experiments/sweep/selection.hpp"
#include "experiments/sweep/state.hpp"

namespace rapid {

struct LocalSweepOptions {
  int workers = 1;
  Selection selection;
  bool force = false;       // rerun the selected cells even if done (not their dependencies)
  double job_timeout_s = 0; // stop a job running longer than this (a failed attempt); 0: never
  std::string binary;       // the rapid executable the jobs run
  bool terminal = false;    // live redraw (stderr is a terminal) rather than log lines
  std::ostream* progress = nullptr;  // where progress goes (stderr)
};

SweepReport run_local_sweep(const SweepFolder& folder, const LocalSweepOptions& options);

}  // namespace rapid
