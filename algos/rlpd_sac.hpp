// RLPD as published (Ball et al. 2023; ikostrikov/rlpd's configs/rlpd_config.py, sac_config.py and
// rlpd/agents/sac/sac_learner.py), beside the paper's reading of it (`rlpd`, the DDPG backbone on
// symmetric batches): SAC with a tanh-squashed Gaussian actor and a learned entropy temperature
// (init_temperature 1, target entropy −A/2, Adam at temperature_lr = 3e-4 on log α, the entropy
// in the critic's target), an ensemble of
// critic_ensemble = 10 LayerNorm critics whose target is the minimum over critic_subset = 2 drawn
// per step, and utd_ratio = 20 critic steps per decision (the critics' targets move after each),
// then one actor step and one temperature step on the last batch; every network starts as rlpd's
// (init = xavier). Its recipe (rlpd_sac_recipe() below) gives these values where a config leaves the
// keys out; network widths, batch, the actor's and critics' learning rates and the budget are the
// profile's, as for every algorithm, so only the method differs (docs/algorithms.md).
//
// Evaluations and checkpoints use the deterministic policy tanh(μ(s)); exploration samples the
// Gaussian with the trainer's exploration stream.
#pragma once

#include "algos/actor_critic.hpp"
#include "core/tanh_gaussian.hpp"

namespace rapid {

inline constexpr MethodKey kUtdRatio{"utd_ratio", MethodKey::kInteger, kPositive,
                                 "critic steps per decision, each on a fresh batch (RLPD's update-to-data ratio)", 1};
inline constexpr MethodKey kInitTemperature{"init_temperature", MethodKey::kNumber, kPositive,
                                        "the entropy temperature α at the start (learned from there)", 0};
inline constexpr MethodKey kTargetEntropyPerDim{"target_entropy_per_dim", MethodKey::kNumber, kAnyNumber,
                                            "the temperature's target entropy is this × the action dimension", 0};
inline constexpr MethodKey kTemperatureLr{"temperature_lr", MethodKey::kNumber, kPositive,
                                      "Adam's learning rate for the temperature's log α (rlpd's temp_lr, not the "
                                      "actor's rate)",
                                      0};

// ikostrikov/rlpd's values: configs/rlpd_config.py (UTD 20, 10 critics, a subset of 2, critic
// LayerNorm), configs/sac_config.py (init_temperature 1, temp_lr 3e-4, target entropy −A/2),
// networks' default_init (xavier).
inline Recipe rlpd_sac_recipe() {
  return {{kUtdRatio.name, 20},          {kCriticEnsemble.name, 10},          {kCriticSubset.name, 2},
          {kInitTemperature.name, 1},    {kTargetEntropyPerDim.name, -0.5}, {kTemperatureLr.name, 3e-4},
          {"critic_layer_norm", true}, {"init", "xavier"}};
}

class RlpdSac : public ActorCritic {
 public:
  RlpdSac(int obs_dim, int act_dim, const AgentConfig& config, std::uint64_t init_seed);

  void explore(const ConstVecRef& obs, Rng& rng, Vec& action) override;
  // utd_ratio critic steps per decision; the actor and the temperature move on the last one's batch.
  UpdateSchedule schedule() const override { return {.steps_per_decision = utd_ratio_, .actor_every = utd_ratio_}; }
  UpdateStats update(const Batch& batch) override;
  // y = r + γ·(1 − terminal)·(min over the subset of Q'_j(s', a') − α·log π(a'|s')), a' ~ π(·|s').
  const RowVec& critic_targets(const Batch& batch) override;

  // The actor loss (1/B) Σ [α·log π(a_b|s_b) − (1/N) Σ_i Q_i(s_b, a_b)], a_b = tanh(μ + σ·noise_b),
  // for a given A × B `noise`: writes its gradient into actor().grads() and returns the loss;
  // changes no parameter (for the finite-difference test).
  float compute_actor_gradient(const Batch& batch, const Mat& noise);
  // The same with noise drawn from the update stream, as an actor step draws it.
  float compute_actor_gradient(const Batch& batch) override;
  // The temperature loss α·(H − H_target) at entropy H, its gradient with respect to log α
  // written into *grad; changes nothing.
  float temperature_loss(float entropy, float* grad) const;
  // One Adam step of log α at temperature_lr on that loss at entropy H (what an actor step ends
  // with, H the entropy of its samples).
  void temperature_step(float entropy);
  float temperature() const;
  float target_entropy() const { return target_entropy_; }

 protected:
  void sync_acting() override;

 private:
  float actor_gradient(const Batch& batch, UpdateStats& stats);
  // noise_ for a batch of `batch`, drawn from the update stream (every sample an update makes).
  void draw_update_noise(int batch);
  void actor_and_temperature_step(const Batch& batch, UpdateStats& stats);

  Mlp sampling_actor_;  // a batch-1 copy of the Gaussian actor, for exploration
  TanhGaussian policy_, next_policy_, exploring_;
  Vec log_temperature_, temperature_grad_;
  Adam temperature_opt_;
  float target_entropy_;
  int utd_ratio_;
  long critic_steps_ = 0;
  Mat noise_, single_noise_, d_q_, d_action_, mean_action_;
  RowVec y_targets_, d_log_prob_, grad_norm_;
};

}  // namespace rapid
