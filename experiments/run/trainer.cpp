#include "experiments/run/trainer.hpp"

#include <algorithm>
#include <string>

#include "core/clock.hpp"
#include "core/statistics.hpp"

namespace rapid {

namespace {

// Running means of UpdateStats over one logging window: the critic's over every learning step,
// the actor's over the steps that updated it (all of them for the paper's five).
struct LossWindow {
  double bc_prior = 0, bc_online = 0, critic = 0, actor = 0, q = 0;
  double q_grad_prior = 0, q_grad_online = 0, bc_grad_prior = 0, bc_grad_online = 0;
  double temperature = 0;
  long n = 0, n_actor = 0;
  void add(const UpdateStats& s) {
    critic += s.critic_loss;
    temperature = s.temperature;
    q += s.q_mean;
    ++n;
    if (!s.actor_updated) return;
    bc_prior += s.bc_prior;
    bc_online += s.bc_online;
    actor += s.actor_loss;
    q_grad_prior += s.q_grad_prior;
    q_grad_online += s.q_grad_online;
    bc_grad_prior += s.bc_grad_prior;
    bc_grad_online += s.bc_grad_online;
    ++n_actor;
  }
  LossPoint flush(long step) {
    const double k = static_cast<double>(n), ka = static_cast<double>(n_actor);
    LossPoint p{step,
                bc_prior / ka,
                bc_online / ka,
                critic / k,
                actor / ka,
                q / k,
                q_grad_prior / ka,
                q_grad_online / ka,
                bc_grad_prior / ka,
                bc_grad_online / ka,
                temperature};
    *this = {};
    return p;
  }
};

}  // namespace

namespace {

// Fills the mean, std and collision rate from the per-episode vectors.
EvalResult& summarise(EvalResult& r) {
  r.return_mean = mean(r.returns);
  r.return_std = population_std(r.returns);
  r.collision_rate = static_cast<double>(std::count(r.collided.begin(), r.collided.end(), true)) /
                     static_cast<double>(r.collided.size());
  return r;
}

// The evaluation of the first `n` of r's episodes.
EvalResult head_of(const EvalResult& r, int n) {
  EvalResult h;
  h.returns.assign(r.returns.begin(), r.returns.begin() + n);
  h.collided.assign(r.collided.begin(), r.collided.begin() + n);
  return summarise(h);
}

}  // namespace

EvalResult evaluate(Env& env, const EvalPolicy& policy, int episodes) {
  Vec obs(env.obs_dim());
  Vec action(env.act_dim());
  EvalResult result;
  for (int e = 0; e < episodes; ++e) {
    env.reset(stream_seed(kEvaluationBaseSeed, Stream::kEnvEval, static_cast<std::uint64_t>(e)), obs);
    double ret = 0;
    bool collided = false;
    for (;;) {
      policy(obs, action);
      const StepResult r = env.step(action, obs);
      ret += r.reward;
      collided = collided || r.info.collision;
      if (r.terminated || r.truncated) break;
    }
    result.returns.push_back(ret);
    result.collided.push_back(collided);
  }
  return summarise(result);
}

EvalResult evaluate(Env& env, ActorCritic& agent, int episodes) {
  return evaluate(env, [&agent](const Vec& obs, VecRef action) { action = agent.act(obs).col(0); }, episodes);
}

long first_update_step(const RunConfig& config, bool with_prior) {
  const long batch = config.agent.batch_size;
  const long online_part = with_prior ? batch - batch / 2 : batch;
  return std::max({config.warmup_steps, online_part, 1L});
}

std::pair<double, double> final_performance(const TrainLog& log, int last_k) {
  std::vector<double> last;
  const int n = static_cast<int>(log.eval.size());
  for (int i = std::max(0, n - last_k); i < n; ++i) last.push_back(log.eval[i].return_mean);
  if (last.empty()) return {0.0, 0.0};  // a run that failed before its first evaluation
  return {mean(last), population_std(last)};
}

namespace {

// One call of train(): the run's buffers, generators and schedules, so that run() reads as
// Algorithm 1 (act, store, learn, log; evaluate and reset at episode boundaries) and each of
// those steps has a name. Everything is allocated here, nothing per decision.
class TrainingRun {
 public:
  TrainingRun(Env& env, ActorCritic& agent, const ReplayBuffer* prior, int return_window, const RunConfig& config,
              std::uint64_t run_seed, TrainLog& log, const TrainHooks& hooks)
      : env_(env),
        agent_(agent),
        config_(config),
        run_seed_(run_seed),
        log_(log),
        hooks_(hooks),
        online_(env.obs_dim(), env.act_dim(), static_cast<std::size_t>(std::min(config.buffer_capacity, config.steps)),
                return_window),
        sampler_(prior, &online_),
        first_update_(first_update_step(config, prior != nullptr)),
        steps_per_decision_(agent.schedule().steps_per_decision),
        explore_rng_(stream_seed(run_seed, Stream::kExploration)),
        sample_rng_(stream_seed(run_seed, Stream::kSampling)),
        obs_(env.obs_dim()),
        next_obs_(env.obs_dim()),
        action_(env.act_dim()) {
    batch_.resize(env.obs_dim(), env.act_dim(), config.agent.batch_size);
  }

  void run() {
    log_ = {};
    last_progress_ = Clock::now();
    evaluate_now(0, 0);
    next_eval_ = config_.eval_every;
    start_episode(0);
    for (long t = 0; t < config_.steps; ++t) {
      choose_action(t);
      const StepResult r = step_env();
      const long done_steps = t + 1;
      if (done_steps >= first_update_) learn(done_steps);
      if (done_steps % config_.bc_log_every == 0 && window_.n > 0) log_losses(done_steps);
      checkpoint_if_due(done_steps);
      const bool last_step = done_steps == config_.steps;
      if (r.terminated || r.truncated || last_step) end_episode(done_steps, r, last_step);
      report_progress(done_steps);
    }
  }

 private:
  // Uniform random during the warm-up (if the config has one), then the agent's exploring action
  // (π(s) plus Gaussian noise, clipped to [-1, 1]; a sample of SAC's policy).
  void choose_action(long t) {
    const int act_dim = static_cast<int>(action_.size());
    if (t < config_.warmup_steps) {
      for (int i = 0; i < act_dim; ++i) action_[i] = static_cast<float>(explore_rng_.uniform(-1.0, 1.0));
      return;
    }
    agent_.explore(obs_, explore_rng_, action_);
  }

  // One decision in the environment: the transition goes into the online buffer and the episode.
  StepResult step_env() {
    const auto t0 = Clock::now();
    const StepResult r = env_.step(action_, next_obs_);
    log_.env_seconds += seconds_since(t0);
    online_.add(obs_, action_, r.reward, next_obs_, r.terminated, r.truncated && !r.terminated);
    episode_.ret += r.reward;
    ++episode_.length;
    episode_.collision = episode_.collision || r.info.collision;
    obs_ = next_obs_;
    ++log_.env_steps;
    return r;
  }

  // The agent's learning steps of one decision, each on a fresh batch (from first_update_ on; the
  // paper's algorithms take one, rlpd-sac utd_ratio). A NaN or inf loss ends the run as diverged.
  void learn(long done_steps) {
    for (int k = 0; k < steps_per_decision_; ++k) {
      const auto t0 = Clock::now();
      sampler_.sample(sample_rng_, batch_);
      const UpdateStats s = agent_.update(batch_);
      log_.update_seconds += seconds_since(t0);
      ++log_.learning_steps;
      if (s.actor_updated) ++log_.updates;
      if (!s.finite)
        throw DivergedError("training diverged at step " + std::to_string(done_steps) + ": critic loss " +
                            std::to_string(s.critic_loss) + ", actor loss " + std::to_string(s.actor_loss));
      window_.add(s);
    }
  }

  // The mean losses of the window that just ended, once no weight has become NaN or inf.
  void log_losses(long done_steps) {
    if (!agent_.parameters_finite())
      throw DivergedError("training diverged at step " + std::to_string(done_steps) + ": a network weight is NaN or inf");
    log_.losses.push_back(window_.flush(done_steps));
  }

  void checkpoint_if_due(long done_steps) {
    if (next_checkpoint_ < hooks_.checkpoint_steps.size() && done_steps == hooks_.checkpoint_steps[next_checkpoint_]) {
      if (hooks_.checkpoint) hooks_.checkpoint(done_steps, log_.updates);
      ++next_checkpoint_;
    }
  }

  // The episode (or the run) ended: keep the episode, evaluate if one is due, start the next.
  // Evaluations happen only here: one simulation per process, so never mid-episode.
  void end_episode(long done_steps, const StepResult& r, bool last_step) {
    if (r.terminated || r.truncated) log_.episodes.push_back(episode_);
    if (done_steps >= next_eval_ || last_step) {
      const long target = last_step ? config_.steps : next_eval_;
      while (next_eval_ <= done_steps) next_eval_ += config_.eval_every;
      evaluate_now(done_steps, std::min(target, config_.steps), last_step);
    }
    if (!last_step) start_episode(done_steps);
  }

  void start_episode(long at_step) {
    env_.reset(stream_seed(run_seed_, Stream::kEnvTrain, episode_index_++), obs_);
    episode_ = {at_step, 0.0, 0, false};
  }

  // `target` is the multiple of eval_every this evaluation stands for (curves align on it). At
  // the end of a run with a final evaluation, one evaluation serves both: the final one runs the
  // same evaluation seeds 0, 1, … as every curve point, with more of them, so the curve's last
  // point is its first eval_episodes episodes.
  void evaluate_now(long step, long target, bool final = false) {
    const auto t0 = Clock::now();
    const bool with_final = final && config_.final_eval_episodes > 0;
    EvalResult r = evaluate(env_, agent_, with_final ? std::max(config_.eval_episodes, config_.final_eval_episodes)
                                                     : config_.eval_episodes);
    if (with_final) {
      log_.final_eval = head_of(r, config_.final_eval_episodes);
      r = head_of(r, config_.eval_episodes);
    }
    log_.eval.push_back({step, target, r.return_mean, r.return_std, r.collision_rate});
    log_.eval_seconds += seconds_since(t0);
  }

  void report_progress(long done_steps) {
    if (!hooks_.progress || seconds_since(last_progress_) < 1.0) return;
    hooks_.progress(done_steps, log_);
    last_progress_ = Clock::now();
  }

  Env& env_;
  ActorCritic& agent_;
  const RunConfig& config_;
  const std::uint64_t run_seed_;
  TrainLog& log_;
  const TrainHooks& hooks_;
  ReplayBuffer online_;
  SymmetricSampler sampler_;
  const long first_update_;
  const int steps_per_decision_;
  Batch batch_;
  Rng explore_rng_, sample_rng_;
  Vec obs_, next_obs_, action_;
  std::uint64_t episode_index_ = 0;
  TrainEpisode episode_;
  long next_eval_ = 0;
  std::size_t next_checkpoint_ = 0;
  LossWindow window_;
  Clock::time_point last_progress_{};
};

}  // namespace

void train(Env& env, ActorCritic& agent, const ReplayBuffer* prior, int return_window, const RunConfig& config,
           std::uint64_t run_seed, TrainLog& log, const TrainHooks& hooks) {
  if (prior != nullptr && prior->empty()) throw std::invalid_argument("the prior buffer is empty");
  if (prior != nullptr && prior->return_window() != return_window)
    throw std::invalid_argument("the prior buffer's return window is " + std::to_string(prior->return_window()) +
                                ", the online buffer's " + std::to_string(return_window));
  TrainingRun(env, agent, prior, return_window, config, run_seed, log, hooks).run();
}

}  // namespace rapid
