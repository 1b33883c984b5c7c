// `rapid bench`, part 4: sweep throughput, N worker processes against one, on a small pendulum
// grid run by `rapid sweep` itself (docs/performance.md: N workers should do N times the work of one).
#pragma once

#include <string>

namespace rapid::bench {

struct SweepBenchOptions {
  int workers = 2;
  int jobs = 8;          // grid cells (ddpg on pendulum, one per seed; 0.5 s each)
  long steps = 5000;     // training steps per cell (a few seconds: process start-up must not dominate)
  int repeats = 3;       // each repeat runs 1 worker and N workers, alternating the order
};

struct SweepBenchResult {
  bool ran = false;
  std::string skipped;           // why not, when !ran
  int workers = 0, jobs = 0;
  double one_worker_s = 0;       // median wall time of the sweep with --jobs 1
  double n_workers_s = 0;        // median wall time with --jobs N
  double speedup = 0;            // one_worker_s / n_workers_s (ideal: N)
};

// Runs this executable's own `sweep` subcommand in fresh folders under a temporary directory.
SweepBenchResult bench_sweep(const SweepBenchOptions& options);

}  // namespace rapid::bench
