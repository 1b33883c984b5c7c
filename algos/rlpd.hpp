// RLPD as the paper uses it: the DDPG backbone with symmetric sampling (B/2 prior + B/2 online)
// and the LayerNorm critic; no imitation term.
#pragma once

#include "algos/actor_critic.hpp"

namespace rapid {

class Rlpd : public ActorCritic {
 public:
  using ActorCritic::ActorCritic;
  std::string name() const override { return "rlpd"; }
  bool uses_prior() const override { return true; }
};

}  // namespace rapid
