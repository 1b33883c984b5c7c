// The DDPG actor-critic backbone every algorithm shares (paper Algorithm 1, eqs. (2)–(3)):
// deterministic tanh actor, critic Q(s, a) with LayerNorm after each hidden layer, target
// networks with Polyak averaging, Adam.
//
// An algorithm is this class plus two answers:
//   bc_weights()   the per-sample weight w_i of the imitation term in the actor loss
//                  L(φ) = −λ·(1/B) Σ Q(s_i, π(s_i)) + (1/B) Σ w_i ‖π(s_i) − a_i‖²
//                  (overridden in the files beside this one, with imitates(); the backbone's is
//                  all zero), and
//   uses_prior     whether half of every batch comes from the prior dataset: its row in
//                  algos/registry.cpp, since the trainer, not the agent, draws the batches.
// λ is 1 unless bc_q_alpha is on and the algorithm imitates (TD3+BC's normalisation, q_weight()).
#pragma once

#include <memory>
#include <optional>

#include "algos/agent_config.hpp"
#include "core/adam.hpp"
#include "core/mlp.hpp"
#include "core/replay_buffer.hpp"

namespace rapid {

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
  bool finite = true;           // false if a loss came out NaN or inf
};

class ActorCritic {
 public:
  ActorCritic(int obs_dim, int act_dim, const AgentConfig& config, std::uint64_t init_seed);
  virtual ~ActorCritic() = default;

  // Deterministic action π(s) for one observation (no allocation after the first call).
  const Mat& act(const ConstVecRef& obs);

  // One gradient step on `batch`: the actor on (2), then the critic on (3), then the targets
  // (Algorithm 1's order).
  UpdateStats update(const Batch& batch);

  // The critic's target y = r + γ·(1 − terminal)·Q'(s', π'(s')); timeouts bootstrap.
  const RowVec& critic_targets(const Batch& batch);

  // Writes dL/dφ of the actor loss (2) on `batch` into actor().grads() and returns L(φ); changes
  // no parameter. Exposed so tests can check the gradient against finite differences.
  float compute_actor_gradient(const Batch& batch);
  // The same with the Q term's weight held at `q_weight` instead of computed from the batch. The
  // gradient treats λ as a constant (no gradient flows through it), so a finite-difference test
  // perturbs this function, with λ fixed at the unperturbed q_weight(batch).
  float compute_actor_gradient(const Batch& batch, float q_weight);
  // λ on `batch` at the current parameters.
  float q_weight(const Batch& batch);

  bool parameters_finite() const;
  const AgentConfig& config() const { return config_; }
  Mlp& actor() { return actor_; }
  Mlp& critic() { return critic_; }

 protected:
  // w_i of the imitation term for each column of `batch` (w has batch.size() entries).
  virtual void bc_weights(const Batch& batch, RowVec& w) const;
  // Whether the actor loss has an imitation term (bc_weights not all zero by construction); only
  // then does bc_q_alpha scale the Q term, so it changes nothing for DDPG and RLPD.
  virtual bool imitates() const { return false; }

 private:
  // λ for the batch's Q(s, π(s)) (a 1 × B row).
  float q_weight_of(const Mat& q) const;
  // Fills pi_ = π(s), dpi_ = dL/dπ(s) and the actor-side fields of `stats`; returns L(φ). λ is
  // `fixed_q_weight` when given, else computed from the batch.
  float actor_objective(const Batch& batch, UpdateStats& stats, std::optional<float> fixed_q_weight);
  // actor_objective, then back-propagates dpi_ into the actor's parameter gradients.
  float actor_gradient(const Batch& batch, UpdateStats& stats, std::optional<float> fixed_q_weight = std::nullopt);
  void actor_step(const Batch& batch, UpdateStats& stats);
  void critic_step(const Batch& batch, UpdateStats& stats);
  // Writes [s; a] into the critic's input buffer.
  const Mat& critic_input(const Mat& obs, const Mat& act);

  AgentConfig config_;
  int obs_dim_, act_dim_;
  Mlp actor_, critic_, actor_target_, critic_target_;
  // A copy of the actor for single observations, so acting (batch 1) and updating (batch B) each
  // keep buffers of one size and neither reallocates; synced lazily after updates.
  Mlp acting_actor_;
  bool acting_actor_stale_ = false;
  Adam actor_opt_, critic_opt_;
  // Preallocated per-update buffers.
  Mat sa_, pi_, dpi_, dq_, single_obs_;
  RowVec y_, w_, sq_err_, grad_norm_;
};

}  // namespace rapid
