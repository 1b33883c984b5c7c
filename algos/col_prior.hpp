// CoL-prior (on symmetric batches, algos/registry.cpp): the backbone plus λ_BC times the mean imitation error over the prior half of the batch.
#pragma once

#include "algos/actor_critic.hpp"

namespace rapid {

// CoL's imitation weight; CoL-all and the Q-filter read it too.
inline constexpr MethodKey kLambdaBc{"lambda_bc", MethodKey::kNumber, kNonNegative, "CoL's imitation weight λ_BC",
                                     std::nullopt};  // every config gives it

class ColPrior : public ActorCritic {
 public:
  using ActorCritic::ActorCritic;

 protected:
  bool imitates() const override { return true; }
  // (1/B) Σ w_i e_i = λ · mean over the prior columns of e_i  ⇔  w_i = λ·B/n_prior there, 0 else.
  void bc_weights(const Batch& batch, const Mat& /*q_pi*/, RowVec& w) override {
    const int n = batch.prior_count;
    w.setZero(batch.size());
    if (n > 0) w.head(n).setConstant(config().method.number(kLambdaBc) * batch.size() / static_cast<float>(n));
  }
};

}  // namespace rapid
