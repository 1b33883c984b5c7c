// RAPID-RL (paper eq. 2, on symmetric batches, algos/registry.cpp): the backbone plus a selective imitation term over the whole batch, each
// transition weighted by relu(r − ε): actions whose reward beats the threshold ε are imitated in
// proportion to the margin, the rest not at all.
#pragma once

#include "algos/actor_critic.hpp"

namespace rapid {

class RapidRl : public ActorCritic {
 public:
  using ActorCritic::ActorCritic;

 protected:
  bool imitates() const override { return true; }
  void bc_weights(const Batch& batch, const Mat& /*q_pi*/, RowVec& w) override {
    w = (batch.rew.array() - config().epsilon).cwiseMax(0.0f).matrix();
  }
};

}  // namespace rapid
