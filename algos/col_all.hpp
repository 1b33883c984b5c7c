// CoL-all (on symmetric batches, algos/registry.cpp): the backbone plus λ_BC times the mean imitation error over the whole batch, online half
// included (so it also imitates its own early, poor actions).
#pragma once

#include "algos/col_prior.hpp"

namespace rapid {

class ColAll : public ActorCritic {
 public:
  using ActorCritic::ActorCritic;

 protected:
  bool imitates() const override { return true; }
  void bc_weights(const Batch& batch, const Mat& /*q_pi*/, RowVec& w) override {
    w.setConstant(batch.size(), config().method.number(kLambdaBc));
  }
};

}  // namespace rapid
