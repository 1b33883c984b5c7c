// RAPID-RL (paper eq. 2, on symmetric batches, algos/registry.cpp): the backbone plus a selective imitation term over the whole batch, each
// transition weighted by relu(r − ε): actions whose reward beats the threshold ε are imitated in
// proportion to the margin, the rest not at all.
#pragma once

#include "algos/actor_critic.hpp"

namespace rapid {

inline constexpr MethodKey kEpsilon{"epsilon", MethodKey::kNumber, kAnyNumber,
                                "RAPID-RL's reward threshold ε, in the scenario's reward units (docs/scenarios.md)",
                                std::nullopt};  // every config gives it

class RapidRl : public ActorCritic {
 public:
  using ActorCritic::ActorCritic;

 protected:
  bool imitates() const override { return true; }
  void bc_weights(const Batch& batch, const Mat& /*q_pi*/, RowVec& w) override {
    w = (batch.rew.array() - config().method.number(kEpsilon)).cwiseMax(0.0f).matrix();
  }
};

}  // namespace rapid
