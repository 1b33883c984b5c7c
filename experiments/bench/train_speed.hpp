// `rapid bench`, part 3: short real training runs through the trainer (experiments/run/trainer.cpp),
// against the rate predicted from what their parts cost alone.
//
// The prediction replays the run's own trajectory: every reset seed and action the training run
// gave the environment is recorded, then sent again to the environment with nothing else running.
// SUMO is deterministic, so the replay visits the same traffic states at their standalone cost;
// updates are timed alone on the same shapes (bench_update). What is left of the gap is the
// harness itself (acting, replay insertion, sampling, bookkeeping) and the parts slowing each
// other down when they alternate (SUMO and the networks share the caches).
#pragma once

#include <string>

#include "experiments/run/config_keys.hpp"

namespace rapid::bench {

struct TrainBenchOptions {
  std::string algo = "rapid-rl";  // trained on a synthetic prior buffer when it needs one
  long steps = 1000;
  long warmup_steps = 100;
  int rounds = 3;                 // each: train, replay, time updates alone; medians are reported
  double update_budget_s = 0.3;   // per round, for the standalone update cost
};

struct TrainBenchResult {
  long env_steps = 0, updates = 0, resets = 0;  // of one training run (evaluation episodes included)
  double train_s = 0;               // wall time of one train() call, evaluations included (median)
  double train_steps_per_s = 0;     // env_steps / train_s (median)
  // env_steps / (replayed env time + updates·t_update): the rate the loop would reach if acting,
  // replay, sampling and bookkeeping cost nothing and the parts did not disturb each other.
  double predicted_steps_per_s = 0;
  double end_to_end_ratio = 0;      // measured / predicted, median over rounds
  double env_share = 0;             // of train_s: env steps and resets, timed in the run
  double update_share = 0;          // of train_s: sampling and updates (the trainer's own timer)
  // Per-call costs alone (replay, bench_update) and inside training (the trainer's timers; its
  // update time includes batch sampling). Inside/alone > 1 is the parts slowing each other down.
  double alone_decision_s = 0, alone_reset_s = 0, alone_update_s = 0;
  double in_run_decision_s = 0, in_run_update_s = 0;
};

TrainBenchResult bench_train(const std::string& scenario, const RunConfig& defaults,
                             const TrainBenchOptions& options);

}  // namespace rapid::bench
