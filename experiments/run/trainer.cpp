#include "experiments/run/trainer.hpp"

#include <algorithm>
#include <string>

#include "core/clock.hpp"
#include "core/statistics.hpp"

namespace rapid {

namespace {

// Running means of UpdateStats over one logging window.
struct LossWindow {
  double bc_prior = 0, bc_online = 0, critic = 0, actor = 0, q = 0;
  long n = 0;
  void add(const UpdateStats& s) {
    bc_prior += s.bc_prior;
    bc_online += s.bc_online;
    critic += s.critic_loss;
    actor += s.actor_loss;
    q += s.q_mean;
    ++n;
  }
  LossPoint flush(long step) {
    const double k = static_cast<double>(n);
    LossPoint p{step, bc_prior / k, bc_online / k, critic / k, actor / k, q / k};
    *this = {};
    return p;
  }
};

}  // namespace

EvalResult evaluate(Env& env, ActorCritic& agent, int episodes) {
  Vec obs(env.obs_dim());
  std::vector<double> returns;
  int collisions = 0;
  for (int e = 0; e < episodes; ++e) {
    env.reset(stream_seed(kEvaluationBaseSeed, Stream::kEnvEval, static_cast<std::uint64_t>(e)), obs);
    double ret = 0;
    bool collided = false;
    for (;;) {
      const StepResult r = env.step(agent.act(obs).col(0), obs);
      ret += r.reward;
      collided = collided || r.info.collision;
      if (r.terminated || r.truncated) break;
    }
    returns.push_back(ret);
    collisions += collided ? 1 : 0;
  }
  return {mean(returns), population_std(returns), static_cast<double>(collisions) / episodes};
}

std::pair<double, double> final_performance(const TrainLog& log, int last_k) {
  std::vector<double> last;
  const int n = static_cast<int>(log.eval.size());
  for (int i = std::max(0, n - last_k); i < n; ++i) last.push_back(log.eval[i].return_mean);
  if (last.empty()) return {0.0, 0.0};  // a run that failed before its first evaluation
  return {mean(last), population_std(last)};
}

void train(Env& env, ActorCritic& agent, const ReplayBuffer* prior, const RunConfig& config,
           std::uint64_t run_seed, TrainLog& log, const TrainHooks& hooks) {
  const int obs_dim = env.obs_dim(), act_dim = env.act_dim();
  if (prior != nullptr && prior->empty()) throw std::invalid_argument("the prior buffer is empty");
  ReplayBuffer online(obs_dim, act_dim, static_cast<std::size_t>(std::min(config.buffer_capacity, config.steps)));
  SymmetricSampler sampler(prior, &online);
  Batch batch;
  batch.resize(obs_dim, act_dim, config.agent.batch_size);
  Rng explore_rng(stream_seed(run_seed, Stream::kExploration));
  Rng sample_rng(stream_seed(run_seed, Stream::kSampling));
  Vec obs(obs_dim), next_obs(obs_dim), action(act_dim);

  log = {};
  LossWindow window;
  const auto t_start = Clock::now();
  auto last_progress = t_start;
  auto run_evaluation = [&](long step, long target) {
    const auto t0 = Clock::now();
    const EvalResult r = evaluate(env, agent, config.eval_episodes);
    log.eval.push_back({step, target, r.return_mean, r.return_std, r.collision_rate});
    log.eval_seconds += seconds_since(t0);
  };

  run_evaluation(0, 0);
  long next_eval = config.eval_every;
  std::size_t next_checkpoint = 0;
  std::uint64_t episode = 0;
  env.reset(stream_seed(run_seed, Stream::kEnvTrain, episode), obs);
  TrainEpisode current{0, 0.0, 0, false};

  for (long t = 0; t < config.steps; ++t) {
    // Act: uniform random during warm-up, then π(s) plus Gaussian noise, clipped to [-1, 1].
    if (t < config.warmup_steps) {
      for (int i = 0; i < act_dim; ++i) action[i] = static_cast<float>(explore_rng.uniform(-1.0, 1.0));
    } else {
      action = agent.act(obs).col(0);
      for (int i = 0; i < act_dim; ++i)
        action[i] = std::clamp(action[i] + static_cast<float>(explore_rng.normal(0.0, config.agent.noise_std)), -1.0f, 1.0f);
    }
    auto t0 = Clock::now();
    const StepResult r = env.step(action, next_obs);
    log.env_seconds += seconds_since(t0);
    online.add(obs, action, r.reward, next_obs, r.terminated, r.truncated && !r.terminated);
    current.ret += r.reward;
    ++current.length;
    current.collision = current.collision || r.info.collision;
    obs = next_obs;
    ++log.env_steps;

    // Learn: one gradient step per environment step after the warm-up.
    if (t + 1 >= config.warmup_steps) {
      t0 = Clock::now();
      sampler.sample(sample_rng, batch);
      const UpdateStats s = agent.update(batch);
      log.update_seconds += seconds_since(t0);
      ++log.updates;
      if (!s.finite)
        throw DivergedError("training diverged at step " + std::to_string(t + 1) + ": critic loss " +
                            std::to_string(s.critic_loss) + ", actor loss " + std::to_string(s.actor_loss));
      window.add(s);
    }
    const long done_steps = t + 1;
    if (done_steps % config.bc_log_every == 0 && window.n > 0) {
      if (!agent.parameters_finite())
        throw DivergedError("training diverged at step " + std::to_string(done_steps) + ": a network weight is NaN or inf");
      log.losses.push_back(window.flush(done_steps));
    }
    if (next_checkpoint < hooks.checkpoint_steps.size() && done_steps == hooks.checkpoint_steps[next_checkpoint]) {
      if (hooks.checkpoint) hooks.checkpoint(done_steps);
      ++next_checkpoint;
    }

    const bool last_step = done_steps == config.steps;
    if (r.terminated || r.truncated || last_step) {
      if (r.terminated || r.truncated) log.episodes.push_back(current);
      // Evaluate at episode boundaries: one simulation per process, so never mid-episode.
      if (done_steps >= next_eval || last_step) {
        long target = last_step ? config.steps : next_eval;
        while (next_eval <= done_steps) next_eval += config.eval_every;
        run_evaluation(done_steps, std::min(target, config.steps));
      }
      if (!last_step) {
        ++episode;
        env.reset(stream_seed(run_seed, Stream::kEnvTrain, episode), obs);
        current = {done_steps, 0.0, 0, false};
      }
    }
    if (hooks.progress && seconds_since(last_progress) >= 1.0) {
      hooks.progress(done_steps, log);
      last_progress = Clock::now();
    }
  }
}

}  // namespace rapid
