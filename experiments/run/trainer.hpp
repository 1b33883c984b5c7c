// The online training loop shared by every algorithm (paper Algorithm 1) and the deterministic
// evaluation. Works on any Env; knows nothing of SUMO or of which algorithm it trains.
#pragma once

#include <functional>
#include <optional>
#include <stdexcept>
#include <vector>

#include "algos/actor_critic.hpp"
#include "envs/env.hpp"
#include "experiments/run/config_keys.hpp"

namespace rapid {

struct EvalPoint {
  long step = 0;         // environment steps when the evaluation ran (an episode boundary)
  long target_step = 0;  // the multiple of eval_every it stands for (curves align on this)
  double return_mean = 0, return_std = 0, collision_rate = 0;
};

struct TrainEpisode {
  long step = 0;  // environment steps at the episode's start
  double ret = 0;
  int length = 0;
  bool collision = false;
};

// Means over the updates of one logging window; NaN where not defined (bc_prior without prior).
// The *_grad fields are the mean per-sample gradient norms at the actor's output of the actor
// loss's two terms (UpdateStats), the prior and online columns apart.
struct LossPoint {
  long step = 0;
  double bc_prior = 0, bc_online = 0, critic_loss = 0, actor_loss = 0, q_mean = 0;
  double q_grad_prior = 0, q_grad_online = 0, bc_grad_prior = 0, bc_grad_online = 0;
  double temperature = 0;  // SAC's entropy temperature α at the window's last step; 0 without one
};

struct EvalResult {
  double return_mean = 0, return_std = 0, collision_rate = 0;
  std::vector<double> returns;  // one per episode, in the order of the evaluation seeds
  std::vector<bool> collided;   // whether that episode had a collision
};

struct TrainLog {
  std::vector<EvalPoint> eval;
  // The final evaluation at T on final_eval_episodes episodes; empty when the config has none
  // (then the final return is the mean of the last K evaluations, final_performance()).
  std::optional<EvalResult> final_eval;
  std::vector<TrainEpisode> episodes;
  std::vector<LossPoint> losses;
  long env_steps = 0;
  long updates = 0;         // actor updates: the gradient steps that made the saved actor
  long learning_steps = 0;  // ActorCritic::update calls (utd_ratio per decision; = updates for the paper's five)
  double env_seconds = 0, update_seconds = 0, eval_seconds = 0;
};

struct TrainHooks {
  std::vector<long> checkpoint_steps;             // call `checkpoint` after these steps
  std::function<void(long step, long updates)> checkpoint;  // updates: gradient steps so far
  std::function<void(long step, const TrainLog&)> progress;  // called now and then (≥ 1 s apart)
};

// Thrown when a loss or a weight becomes NaN or inf.
class DivergedError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A policy as evaluate() asks it: writes the action for `obs` into `action` (act_dim entries).
using EvalPolicy = std::function<void(const Vec& obs, VecRef action)>;

// The evaluation protocol: `episodes` episodes of `policy` on the fixed evaluation seeds (the
// same traffic for every run, algorithm and language: the Python module scores its policies here).
EvalResult evaluate(Env& env, const EvalPolicy& policy, int episodes);

// The agent's deterministic policy evaluated so.
EvalResult evaluate(Env& env, ActorCritic& agent, int episodes);

// The first decision after which the agent updates (Algorithm 1's start): once `warmup_steps`
// decisions have passed (0: none; before them, actions are uniform random) and the online buffer
// holds the online part of a batch (B − B/2 with a prior dataset, B without). One update per
// decision from then on, so after decision t ≥ this step the agent has had t − step + 1 updates.
long first_update_step(const RunConfig& config, bool with_prior);

// Trains `agent` online for config.steps decisions. With a `prior` buffer (for the algorithms
// whose registry row says uses_prior), every batch is half prior, half online; null: all online.
// The online buffer computes Batch::ret over `return_window` decisions (the algorithm's
// Algorithm::return_window), which a prior buffer must share so both halves mean the same.
// Fills `log` as it goes, so a run that throws (DivergedError, a simulator error) keeps the
// curves it had measured.
void train(Env& env, ActorCritic& agent, const ReplayBuffer* prior, int return_window, const RunConfig& config,
           std::uint64_t run_seed, TrainLog& log, const TrainHooks& hooks = {});

// The mean and std of the last K evaluations' mean returns (the final return when the config
// has no final evaluation).
std::pair<double, double> final_performance(const TrainLog& log, int last_k);

}  // namespace rapid
