// Hyper-parameters of the actor-critic backbone. Each field, and each method key, is a row of the
// run config's key table (experiments/run/config_keys.cpp: what it means, which values it
// accepts); the values runs use come from a profile's config (experiments/configs/<profile>/shared.json
// and each scenario's own, in its scenario.json). There are no
// defaults here on purpose: a value that does not come from a config file must never reach a run
// unnoticed.
#pragma once

#include <vector>

#include "algos/method_key.hpp"
#include "core/mlp.hpp"

namespace rapid {

struct AgentConfig {
  std::vector<int> actor_hidden;
  std::vector<int> critic_hidden;
  float actor_lr{};
  float critic_lr{};
  float gamma{};
  float tau{};
  int batch_size{};  // B; with a prior dataset B/2 prior + B/2 online
  float noise_std{};
  // The keys of the methods and of the backbone's optional pieces (ε, λ_BC, the critic ensemble,
  // …), each declared beside the code that reads it (algos/method_key.hpp); absent: not given.
  MethodValues method;
  // How the networks are built and start (optional keys every algorithm reads; neutral values are
  // the paper's five's, and a published baseline's recipe sets its code's): LayerNorm after each
  // hidden layer of the critics, and the initialisation scheme of every network (core/mlp.hpp).
  bool critic_layer_norm{};
  WeightInit init{};
};

}  // namespace rapid
