// The DDPG actor-critic backbone every algorithm shares (paper Algorithm 1, eqs. (2)–(3)):
// deterministic tanh actor, critics Q(s, a) with LayerNorm after each hidden layer (the paper's
// §III-B2; critic_layer_norm turns it off), target networks with Polyak averaging, Adam.
//
// The critics are an ensemble of critic_ensemble members (1 for the paper's five), and the target
// of eq. (3) takes the minimum over critic_subset of the target members drawn afresh for every
// update (all of them when the subset is the whole ensemble: TD3's twin minimum). The actor's Q
// term reads the first member (TD3's Q1). An algorithm with another update rule (TD3's delayed
// actor, SAC's stochastic actor and temperature) overrides update() and the pieces below, in one
// file beside this one (td3_bc.hpp, rlpd_sac.hpp).
//
// The paper's algorithms are this class plus two answers:
//   bc_weights()   the per-sample weight w_i of the imitation term in the actor loss
//                  L(φ) = −λ·(1/B) Σ Q(s_i, π(s_i)) + (1/B) Σ w_i ‖π(s_i) − a_i‖²
//                  (overridden in the files beside this one, with imitates(); the backbone's is
//                  all zero). It may read the critic: Q1(s, π(s)) as the Q term saw it, and
//                  Q1 at any actions through first_critic() (the Q-filter's Q1(s, a)); the
//                  weights are constants of the step, no gradient flows through them. And
//   uses_prior     whether half of every batch comes from the prior dataset: its row in
//                  algos/registry.cpp, since the trainer, not the agent, draws the batches.
// λ is 1 unless bc_q_alpha is on and the algorithm imitates (TD3+BC's normalisation, q_weight()).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "algos/agent_config.hpp"
#include "algos/method_key.hpp"
#include "core/adam.hpp"
#include "core/critic_ensemble.hpp"
#include "core/mlp.hpp"
#include "core/replay_buffer.hpp"
#include "core/rng.hpp"

namespace rapid {

// The backbone's optional pieces, each off at its neutral value for the paper's five; td3-bc's and
// rlpd-sac's recipes switch them on (algos/registry.cpp lists which algorithms read them).
inline constexpr MethodKey kCriticEnsemble{
    "critic_ensemble", MethodKey::kInteger, kPositive,
    "number N of critics; the actor's Q term reads the first (TD3's Q1), rlpd-sac's their mean", 1};
inline constexpr MethodKey kCriticSubset{
    "critic_subset", MethodKey::kInteger, kPositive,
    "target critics M ≤ N drawn afresh per step, the target taking their minimum (M = N: all, undrawn)", 1};
inline constexpr MethodKey kTargetNoise{"target_noise", MethodKey::kNumber, kNonNegative,
                                    "std of the Gaussian noise on the target action (TD3's target policy smoothing)", 0};
inline constexpr MethodKey kTargetNoiseClip{"target_noise_clip", MethodKey::kNumber, kNonNegative,
                                        "the target noise clipped to ±this", 0};
inline constexpr MethodKey kBcQAlpha{
    "bc_q_alpha", MethodKey::kNumber, kNonNegative,
    "TD3+BC's α: an algorithm with an imitation term scales its actor loss's Q term by λ = α / (mean absolute "
    "Q(s, π(s)) over the batch); 0: off (no scaling)",
    0};

// The backbone's critic pieces as a config gives them: no default stands in for a missing value
// (agent_config.hpp), so critic_ensemble below 1, or critic_subset outside 1..critic_ensemble, is
// refused with std::invalid_argument naming the key. ActorCritic's constructor and Algorithm::check
// (the config-time check) both ask this.
void check_critic_settings(const AgentConfig& config);

// What one gradient step measured; the unweighted BC losses feed Figure 3(b).
struct UpdateStats {
  float critic_loss = 0.0f;
  float actor_loss = 0.0f;      // the whole actor objective, BC term included
  float bc_term = 0.0f;         // (1/B) Σ w_i ‖π(s_i) − a_i‖²
  float q_weight = 1.0f;        // λ, the Q term's weight in the actor loss
  float q_mean = 0.0f;          // mean Q(s, a) over the batch
  float bc_prior = 0.0f;        // mean ‖π(s) − a‖² over the prior columns (NaN if none)
  float bc_online = 0.0f;       // mean ‖π(s) − a‖² over the online columns
  // The sizes of the two forces on the actor, at its output: per sample, the gradient of the Q
  // term, λ‖∂Q(s, a)/∂a‖ at a = π(s), and of the imitation term, ‖2·w·(π(s) − a)‖, each averaged
  // over the prior columns and over the online columns (NaN for a half the batch does not have).
  float q_grad_prior = 0.0f, q_grad_online = 0.0f;
  float bc_grad_prior = 0.0f, bc_grad_online = 0.0f;
  // Whether this step updated the actor (every step of the paper's five; one in policy_delay of
  // TD3's, one in utd_ratio of RLPD's). The actor-side fields above are only set when it did.
  bool actor_updated = true;
  float temperature = 0.0f;     // SAC's entropy temperature α after the step (0 without one)
  bool finite = true;           // false if a loss came out NaN or inf
};

// An algorithm's update schedule: how many learning steps (update() calls, each on a fresh batch)
// it takes per decision, and once per how many of them its actor moves. The trainer and the
// benchmarks ask the agent; no one else reads the keys that set it (utd_ratio, policy_delay).
struct UpdateSchedule {
  int steps_per_decision = 1;
  int actor_every = 1;
};

class ActorCritic {
 public:
  // The networks are initialised from `init_seed`; the randomness of the updates themselves (the
  // target's critic subset, TD3's target noise, SAC's samples) comes from its own stream,
  // stream_seed(init_seed, Stream::kUpdate), which the paper's five never draw from.
  ActorCritic(int obs_dim, int act_dim, const AgentConfig& config, std::uint64_t init_seed);
  virtual ~ActorCritic() = default;

  // The deterministic action for one observation, the one evaluations take: π(s) (no allocation
  // after the first call).
  const Mat& act(const ConstVecRef& obs);
  // The exploring action for one observation during training, into `action`: π(s) plus Gaussian
  // noise of std noise_std from `rng`, clipped to [-1, 1].
  virtual void explore(const ConstVecRef& obs, Rng& rng, Vec& action);

  // One learning step per decision, moving the actor every time (the paper's five).
  virtual UpdateSchedule schedule() const { return {}; }
  // One learning step on `batch` (the trainer calls it schedule().steps_per_decision times per
  // decision, each on a fresh batch): the actor on (2), then the critic on (3), then the targets
  // (Algorithm 1's order).
  virtual UpdateStats update(const Batch& batch);

  // The critic's target y = r + γ·(1 − terminal)·min over the subset of Q'_j(s', π'(s')), with
  // TD3's clipped noise on π'(s') when target_noise > 0; timeouts bootstrap.
  virtual const RowVec& critic_targets(const Batch& batch);

  // Saves the deterministic policy act() runs as a network checkpoint (Mlp::save): what datasets
  // and `rapid rollout --policy` load.
  void save_policy(const std::string& path, std::int64_t updates);

  // Writes dL/dφ of the actor loss (2) on `batch` into actor().grads() and returns L(φ); changes
  // no parameter. Exposed so tests can check the gradient against finite differences.
  virtual float compute_actor_gradient(const Batch& batch);
  // The same with the Q term's weight held at `q_weight` instead of computed from the batch. The
  // gradient treats λ as a constant (no gradient flows through it), so a finite-difference test
  // perturbs this function, with λ fixed at the unperturbed q_weight(batch).
  float compute_actor_gradient(const Batch& batch, float q_weight);
  // λ on `batch` at the current parameters.
  float q_weight(const Batch& batch);

  bool parameters_finite() const;
  const AgentConfig& config() const { return config_; }
  Mlp& actor() { return actor_; }
  // The first critic (the only one of the paper's five); critics() is the whole ensemble.
  Mlp& critic() { return critics_.member(0); }
  CriticEnsemble& critics() { return critics_; }
  Mlp& actor_target() { return actor_target_; }
  CriticEnsemble& target_critics() { return critics_target_; }

 protected:
  // w_i of the imitation term for each column of `batch` (w has batch.size() entries); `q_pi` is
  // Q1(s, π(s)) per column (1 × B), the Q term's, held apart so that first_critic() may run.
  virtual void bc_weights(const Batch& batch, const Mat& q_pi, RowVec& w);
  // Whether the actor loss has an imitation term (bc_weights not all zero by construction); only
  // then does bc_q_alpha scale the Q term, so it changes nothing for DDPG and RLPD.
  virtual bool imitates() const { return false; }

  // The means of `v` over its first `n_prior` entries (a batch's prior columns) and over the
  // rest; NaN for an empty part.
  static void split_means(const RowVec& v, int n_prior, float& prior, float& online);

  // The steps update() is made of, for the algorithms that order them differently.
  void actor_step(const Batch& batch, UpdateStats& stats);
  // The critics on (3) towards critic_targets(batch): the mean over members and columns of
  // (Q_i(s, a) − y)².
  void critic_step(const Batch& batch, UpdateStats& stats);
  void soft_update_targets();  // the actor's and the critics' targets by τ
  // min over `subset` target critics of Q'(s', a') (1 × B), the subset drawn from update_rng()
  // (every member, undrawn, when the subset is the ensemble).
  const RowVec& target_q(const Mat& next_obs, const Mat& next_act);
  // Writes [s; a] into the critic's input buffer.
  const Mat& critic_input(const Mat& obs, const Mat& act);
  // Q1(s, a) of the first critic per column (1 × B), in the critic's output buffer: valid until
  // the critic runs again.
  const Mat& first_critic(const Mat& obs, const Mat& act);
  // Marks the acting copies out of date after the actor changed; sync_acting() refreshes them.
  void actor_changed() { acting_stale_ = true; }
  // Copies the actor's parameters into the network act() runs, acting_network() (a batch-1 copy
  // of the actor here); called by act() and save_policy() when the actor changed since.
  virtual void sync_acting();
  void sync_acting_if_stale();
  Mlp& acting_network() { return acting_actor_; }
  Rng& update_rng() { return update_rng_; }
  int act_dim() const { return act_dim_; }
  Adam& actor_optimiser() { return actor_opt_; }
  // With its own actor network instead of the deterministic tanh actor, and the network act()
  // runs (SAC's Gaussian head and its mean's tanh); initialised like the backbone's, its last
  // layer read as `actor_heads` heads side by side (Mlp::init).
  ActorCritic(int obs_dim, int act_dim, const AgentConfig& config, std::uint64_t init_seed, Mlp actor, Mlp acting,
              int actor_heads = 1);

 private:
  // λ for the batch's Q(s, π(s)) (a 1 × B row).
  float q_weight_of(const Mat& q) const;
  // Fills pi_ = π(s), dpi_ = dL/dπ(s) and the actor-side fields of `stats`; returns L(φ). λ is
  // `fixed_q_weight` when given, else computed from the batch.
  float actor_objective(const Batch& batch, UpdateStats& stats, std::optional<float> fixed_q_weight);
  // actor_objective, then back-propagates dpi_ into the actor's parameter gradients.
  float actor_gradient(const Batch& batch, UpdateStats& stats, std::optional<float> fixed_q_weight = std::nullopt);

  AgentConfig config_;
  int obs_dim_, act_dim_;
  Mlp actor_, actor_target_;
  CriticEnsemble critics_, critics_target_;
  // A copy of the actor for single observations, so acting (batch 1) and updating (batch B) each
  // keep buffers of one size and neither reallocates; synced lazily after updates.
  Mlp acting_actor_;
  bool acting_stale_ = false;
  Adam actor_opt_;
  Rng update_rng_;
  // The backbone's optional pieces as the config sets them (read once: update() runs per decision).
  int critic_subset_;
  float target_noise_std_, target_noise_clip_, bc_q_alpha_;
  // Preallocated per-update buffers.
  Mat sa_, pi_, q_pi_, dpi_, dq_pi_, dq_, single_obs_, target_noise_;
  RowVec y_, w_, sq_err_, grad_norm_, next_q_;
  std::vector<int> actor_q_member_ = {0}, target_subset_;
};

}  // namespace rapid
