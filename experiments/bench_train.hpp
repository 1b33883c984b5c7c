// `rapid bench`, part 3: a short real training run through the trainer (experiments/trainer.cpp),
// against the rate predicted from the separately measured costs of its parts.
#pragma once

#include <string>

#include "experiments/run_config.hpp"

namespace rapid::bench {

struct TrainBenchOptions {
  std::string algo = "rapid-rl";  // trained on a synthetic prior buffer when it needs one
  long steps = 400;
  long warmup_steps = 50;
};

// The separately measured costs the prediction is built from (seconds).
struct PartCosts {
  double decision_s = 0;  // one env decision (bench_env)
  double reset_s = 0;     // one env reset (bench_env)
  double update_s = 0;    // one gradient update of `algo` at the scenario's sizes (bench_update)
};

struct TrainBenchResult {
  long env_steps = 0, updates = 0, resets = 0;
  double train_s = 0;               // wall time of train() minus its evaluations
  double train_steps_per_s = 0;     // env_steps / train_s
  // env_steps / (env_steps·t_decision + updates·t_update + resets·t_reset): what the loop would do
  // if acting, replay, sampling and bookkeeping cost nothing.
  double predicted_steps_per_s = 0;
  double end_to_end_ratio = 0;      // measured / predicted
  double env_share = 0, update_share = 0;  // of train_s, from the trainer's own timers
  // The same costs as the trainer's own timers saw them inside the run (sampling included in the
  // update): where they differ from PartCosts, the parts slow each other down (caches, traffic).
  double in_run_decision_s = 0, in_run_update_s = 0;
};

TrainBenchResult bench_train(const std::string& scenario, const RunConfig& defaults, const PartCosts& costs,
                             const TrainBenchOptions& options);

}  // namespace rapid::bench
