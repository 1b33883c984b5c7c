#include "experiments/bench/train_speed.hpp"

#include "experiments/run/run_config.hpp"

#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "algos/rapid_rl.hpp"
#include "algos/registry.hpp"
#include "envs/env.hpp"
#include "experiments/bench/synthetic.hpp"
#include "experiments/bench/timing.hpp"
#include "experiments/bench/update_speed.hpp"
#include "experiments/run/trainer.hpp"

namespace rapid::bench {

namespace {

// What one pass over a trajectory cost, and its size.
struct TrajectoryCost {
  long steps = 0, resets = 0;
  double step_s = 0, reset_s = 0;
};

// Forwards every call to a real environment, timing it and recording what was asked (reset seeds
// and actions), so that replay() can send exactly the same calls again with nothing else running.
class RecordingEnv final : public Env {
 public:
  RecordingEnv(Env& inner, long expected_steps) : inner_(inner) {
    actions_.reserve(static_cast<std::size_t>(expected_steps * inner.act_dim()));
    calls_.reserve(static_cast<std::size_t>(expected_steps));
  }

  std::string name() const override { return inner_.name(); }
  int obs_dim() const override { return inner_.obs_dim(); }
  int act_dim() const override { return inner_.act_dim(); }
  int horizon() const override { return inner_.horizon(); }

  void reset(std::uint64_t seed, VecRef obs) override {
    calls_.push_back({true, seed, 0.0f});
    const auto t0 = Clock::now();
    inner_.reset(seed, obs);
    in_run_.reset_s += seconds_since(t0);
    ++in_run_.resets;
  }
  StepResult step(const ConstVecRef& action, VecRef obs) override {
    actions_.insert(actions_.end(), action.data(), action.data() + action.size());
    const auto t0 = Clock::now();
    const StepResult r = inner_.step(action, obs);
    in_run_.step_s += seconds_since(t0);
    ++in_run_.steps;
    calls_.push_back({false, 0, r.reward});
    return r;
  }

  const TrajectoryCost& in_run() const { return in_run_; }

  // The recorded calls again, on `env` alone (the same scenario), timed the same way. Throws if
  // a reward differs: the replay would then be timing some other trajectory.
  TrajectoryCost replay(Env& env) const {
    Vec obs(env.obs_dim());
    const int act_dim = env.act_dim();
    TrajectoryCost c;
    std::size_t next_action = 0;
    for (const Call& call : calls_) {
      const auto t0 = Clock::now();
      if (call.reset) {
        env.reset(call.seed, obs);
        c.reset_s += seconds_since(t0);
        ++c.resets;
      } else {
        const StepResult r = env.step(Eigen::Map<const Vec>(actions_.data() + next_action, act_dim), obs);
        c.step_s += seconds_since(t0);
        if (r.reward != call.reward)
          throw std::runtime_error("bench: replaying the training run's actions in " + env.name() +
                                   " gave a different reward at step " + std::to_string(c.steps) +
                                   " (the environment is not deterministic)");
        ++c.steps;
        next_action += static_cast<std::size_t>(act_dim);
      }
    }
    return c;
  }

 private:
  struct Call {
    bool reset;
    std::uint64_t seed;  // of a reset
    float reward;        // of a step: what the replay must reproduce
  };
  Env& inner_;
  std::vector<Call> calls_;
  std::vector<float> actions_;
  TrajectoryCost in_run_;
};

}  // namespace

TrainBenchResult bench_train(const std::string& scenario, const RunConfig& defaults, const TrainBenchOptions& o) {
  RunConfig config = defaults;
  config.steps = o.steps;
  config.warmup_steps = o.warmup_steps;
  // train() evaluates at the start and at the end; one short evaluation each, part of the run.
  config.eval_every = std::numeric_limits<long>::max() / 2;
  config.eval_episodes = 1;
  std::unique_ptr<Env> env = make_run_env(scenario, defaults);
  const int obs_dim = env->obs_dim(), act_dim = env->act_dim();
  const UpdateBenchOptions update_options{.budget_s = o.update_budget_s, .block = 10, .min_rounds = 2};

  TrainBenchResult res;
  std::vector<double> train_s, predicted_s, ratios, env_share, update_share;
  std::vector<double> alone_decision, alone_reset, alone_update, in_run_decision, in_run_update;
  for (int round = 0; round < o.rounds; ++round) {
    // The same seeds every round: the same run, so the rounds differ only by machine noise.
    const Algorithm& algo = find_algorithm(o.algo);
    auto agent = algo.make(obs_dim, act_dim, config.agent, stream_seed(7, Stream::kNetworkInit));
    const int return_window = algo.return_window(config.agent);
    ReplayBuffer prior;
    if (algo.uses_prior) prior = synthetic_replay(obs_dim, act_dim, 4096, config.agent.method.number(kEpsilon), 21, return_window);
    RecordingEnv recorder(*env, o.steps + 4L * env->horizon());
    TrainLog log;
    const auto t0 = Clock::now();
    train(recorder, *agent, algo.uses_prior ? &prior : nullptr, return_window, config, /*run_seed=*/7, log);
    const double wall = seconds_since(t0);

    const TrajectoryCost alone = recorder.replay(*env);
    const UpdateBenchResult u = bench_update(o.algo, obs_dim, act_dim, config.agent, update_options);
    const double predicted = alone.step_s + alone.reset_s + static_cast<double>(log.learning_steps) * u.update_s;

    res.env_steps = alone.steps;
    res.resets = alone.resets;
    res.updates = log.learning_steps;
    train_s.push_back(wall);
    predicted_s.push_back(predicted);
    ratios.push_back(predicted / wall);
    env_share.push_back((recorder.in_run().step_s + recorder.in_run().reset_s) / wall);
    update_share.push_back(log.update_seconds / wall);
    alone_decision.push_back(alone.step_s / static_cast<double>(alone.steps));
    alone_reset.push_back(alone.reset_s / static_cast<double>(alone.resets));
    alone_update.push_back(u.update_s);
    in_run_decision.push_back(recorder.in_run().step_s / static_cast<double>(recorder.in_run().steps));
    in_run_update.push_back(log.learning_steps > 0 ? log.update_seconds / static_cast<double>(log.learning_steps)
                                                   : 0.0);
  }
  res.train_s = median(train_s);
  res.train_steps_per_s = static_cast<double>(res.env_steps) / res.train_s;
  res.predicted_steps_per_s = static_cast<double>(res.env_steps) / median(predicted_s);
  res.end_to_end_ratio = median(ratios);
  res.env_share = median(env_share);
  res.update_share = median(update_share);
  res.alone_decision_s = median(alone_decision);
  res.alone_reset_s = median(alone_reset);
  res.alone_update_s = median(alone_update);
  res.in_run_decision_s = median(in_run_decision);
  res.in_run_update_s = median(in_run_update);
  return res;
}

}  // namespace rapid::bench
