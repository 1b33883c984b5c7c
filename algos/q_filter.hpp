// Q-filter (Nair et al. 2018, "Overcoming Exploration in Reinforcement Learning with
// Demonstrations", arXiv 1709.10089, §IV-C eq. 5) on the paper's backbone: CoL-prior's imitation
// of the prior half of the batch, kept only where the critic rates the dataset's action above the
// actor's, Q1(s, a) > Q1(s, π(s)). The critic-based selection beside RAPID-RL's reward-based
// one: both imitate some prior actions and not others, this one by what the critic has learned,
// RAPID-RL by the step's reward against ε. The mask is a constant of the step (no gradient flows
// through it, as in the paper's filter); λ_BC and the Q term's scale are CoL-prior's keys.
#pragma once

#include "algos/col_prior.hpp"

namespace rapid {

class QFilter : public ActorCritic {
 public:
  using ActorCritic::ActorCritic;

 protected:
  bool imitates() const override { return true; }
  // CoL-prior's w_i = λ·B/n_prior on a prior column, times 1[Q1(s_i, a_i) > Q1(s_i, π(s_i))].
  void bc_weights(const Batch& batch, const Mat& q_pi, RowVec& w) override {
    const int n = batch.prior_count;
    w.setZero(batch.size());
    if (n == 0) return;
    const Mat& q_data = first_critic(batch.obs, batch.act);
    const float weight = config().method.number(kLambdaBc) * batch.size() / static_cast<float>(n);
    for (int i = 0; i < n; ++i) w[i] = q_data(0, i) > q_pi(0, i) ? weight : 0.0f;
  }
};

}  // namespace rapid
