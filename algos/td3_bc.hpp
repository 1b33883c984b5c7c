// TD3+BC (Fujimoto & Gu 2021, sfujim/TD3_BC), used online on symmetric batches as the regularised
// baseline readers expect: the backbone with twin critics whose minimum is the target
// (critic_ensemble 2, critic_subset 2), target policy smoothing (target_noise 0.2 clipped to
// ±0.5), the actor and the targets moving once per policy_delay = 2 critic steps, and the actor
// loss −λ·Q1(s, π(s)) + mean over the batch and the action's entries of (π(s) − a)², with
// λ = α / mean |Q1(s, π(s))| and α = bc_q_alpha = 2.5. Its recipe (td3_bc_recipe() below) gives
// these values where a config leaves the keys out. Unlike the offline original, states are not
// normalised (the online buffer has no fixed statistics), as for every algorithm here.
#pragma once

#include <cmath>

#include "algos/actor_critic.hpp"

namespace rapid {

inline constexpr MethodKey kPolicyDelay{"policy_delay", MethodKey::kInteger, kPositive,
                                        "the actor and the targets move once per this many critic steps (TD3)", 1};

// sfujim/TD3_BC's values (TD3_BC.py and main.py): twin critics and their minimum, target policy
// smoothing, the delay, α = 2.5; its critics have no LayerNorm and its Linear layers start as
// torch.nn.Linear's.
inline Recipe td3_bc_recipe() {
  return {{kCriticEnsemble.name, 2}, {kCriticSubset.name, 2},        {kPolicyDelay.name, 2},
          {kTargetNoise.name, 0.2},  {kTargetNoiseClip.name, 0.5}, {kBcQAlpha.name, 2.5},
          {"critic_layer_norm", false}, {"init", "pytorch"}};
}

class Td3Bc : public ActorCritic {
 public:
  Td3Bc(int obs_dim, int act_dim, const AgentConfig& config, std::uint64_t init_seed)
      : ActorCritic(obs_dim, act_dim, config, init_seed), policy_delay_(config.method.integer(kPolicyDelay)) {}

  UpdateSchedule schedule() const override { return {.steps_per_decision = 1, .actor_every = policy_delay_}; }
  // TD3's order: the critics, then every policy_delay-th step the actor and the targets.
  UpdateStats update(const Batch& batch) override {
    UpdateStats stats;
    critic_step(batch, stats);
    stats.actor_updated = ++critic_steps_ % policy_delay_ == 0;
    if (stats.actor_updated) {
      actor_step(batch, stats);
      soft_update_targets();
    }
    stats.finite = std::isfinite(stats.critic_loss) && std::isfinite(stats.actor_loss);
    return stats;
  }

 protected:
  bool imitates() const override { return true; }
  // TD3+BC's F.mse_loss(π(s), a) averages over the action's entries as well as the batch.
  void bc_weights(const Batch& batch, const Mat& /*q_pi*/, RowVec& w) override {
    w.setConstant(batch.size(), 1.0f / static_cast<float>(act_dim()));
  }

 private:
  int policy_delay_;
  long critic_steps_ = 0;
};

}  // namespace rapid
