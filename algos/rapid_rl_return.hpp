// RAPID-RL (return) (on symmetric batches, algos/registry.cpp): RAPID-RL with each transition's
// imitation weight taken from where it leads rather than from its own step: relu(Ḡ − ε), Ḡ the
// mean reward over the next `return_horizon` decisions of its episode (Batch::ret, computed by the
// replay buffers). A step that pays now but leads into a collision a second later is pulled below
// ε by the collision's reward. Ḡ is a mean of per-step rewards, in the same units as r, so the
// same ε applies.
#pragma once

#include "algos/rapid_rl.hpp"

namespace rapid {

inline constexpr MethodKey kReturnHorizon{
    "return_horizon", MethodKey::kInteger, kPositive,
    "RAPID-RL (return)'s window n: it imitates a transition by relu(Ḡ − ε), Ḡ the mean reward over the next n "
    "decisions of its episode; absent: not given, and rapid-rl-return refuses to run",
    0};

class RapidRlReturn : public ActorCritic {
 public:
  using ActorCritic::ActorCritic;

 protected:
  bool imitates() const override { return true; }
  void bc_weights(const Batch& batch, const Mat& /*q_pi*/, RowVec& w) override {
    w = (batch.ret.array() - config().method.number(kEpsilon)).cwiseMax(0.0f).matrix();
  }
};

}  // namespace rapid
