#include "experiments/bench_train.hpp"

#include <limits>
#include <memory>

#include "algos/registry.hpp"
#include "envs/env.hpp"
#include "experiments/bench_synthetic.hpp"
#include "experiments/bench_timing.hpp"
#include "experiments/trainer.hpp"

namespace rapid::bench {

TrainBenchResult bench_train(const std::string& scenario, const RunConfig& defaults, const PartCosts& costs,
                             const TrainBenchOptions& o) {
  std::unique_ptr<Env> env = make_env(scenario);
  RunConfig config = defaults;
  config.steps = o.steps;
  config.warmup_steps = o.warmup_steps;
  // train() evaluates at the start and at the end; one short evaluation each, subtracted below.
  config.eval_every = std::numeric_limits<long>::max() / 2;
  config.eval_episodes = 1;
  auto agent = make_agent(o.algo, env->obs_dim(), env->act_dim(), config.agent, stream_seed(7, Stream::kNetworkInit));
  ReplayBuffer prior;
  if (agent->uses_prior()) prior = synthetic_replay(env->obs_dim(), env->act_dim(), 4096, config.agent.epsilon, 21);

  TrainLog log;
  const auto t0 = Clock::now();
  train(*env, *agent, agent->uses_prior() ? &prior : nullptr, config, /*run_seed=*/7, log);
  const double wall = seconds_since(t0);

  TrainBenchResult res;
  res.env_steps = log.env_steps;
  res.updates = log.updates;
  // One reset opens the run; every episode that ended before the last step is followed by one.
  res.resets = 1;
  for (const TrainEpisode& e : log.episodes)
    if (e.step + e.length < config.steps) ++res.resets;
  res.train_s = wall - log.eval_seconds;
  res.train_steps_per_s = res.env_steps / res.train_s;
  const double predicted_s =
      res.env_steps * costs.decision_s + res.updates * costs.update_s + res.resets * costs.reset_s;
  res.predicted_steps_per_s = res.env_steps / predicted_s;
  res.end_to_end_ratio = res.train_steps_per_s / res.predicted_steps_per_s;
  res.env_share = log.env_seconds / res.train_s;
  res.update_share = log.update_seconds / res.train_s;
  res.in_run_decision_s = log.env_seconds / static_cast<double>(log.env_steps);
  res.in_run_update_s = log.updates > 0 ? log.update_seconds / static_cast<double>(log.updates) : 0.0;
  return res;
}

}  // namespace rapid::bench
