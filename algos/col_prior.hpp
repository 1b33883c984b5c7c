// CoL-prior (on symmetric batches, algos/registry.cpp): the backbone plus λ_BC times the mean imitation error over the prior half of the batch.
#pragma once

#include "algos/actor_critic.hpp"

namespace rapid {

class ColPrior : public ActorCritic {
 public:
  using ActorCritic::ActorCritic;

 protected:
  bool imitates() const override { return true; }
  // (1/B) Σ w_i e_i = λ · mean over the prior columns of e_i  ⇔  w_i = λ·B/n_prior there, 0 else.
  void bc_weights(const Batch& batch, const Mat& /*q_pi*/, RowVec& w) override {
    const int n = batch.prior_count;
    w.setZero(batch.size());
    if (n > 0) w.head(n).setConstant(config().lambda_bc * batch.size() / static_cast<float>(n));
  }
};

}  // namespace rapid
