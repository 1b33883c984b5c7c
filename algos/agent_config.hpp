// Hyper-parameters of the actor-critic backbone. Each field is a row of the run config's key
// table (experiments/run/config_keys.cpp: what it means, which values it accepts); the values runs
// use come from experiments/configs/<scenario>.json. There are no defaults here on purpose: a
// value that does not come from a config file must never reach a run unnoticed.
#pragma once

#include <vector>

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
  float lambda_bc{};
  float epsilon{};   // RAPID-RL's reward threshold ε
  float bc_q_alpha{};  // TD3+BC's α of the Q term's scale λ; 0: off (an optional key, absent means 0)
  // RAPID-RL (return)'s window n in decisions; 0: not given (an optional key that rapid-rl-return
  // needs; algos/registry.hpp, Algorithm::return_window).
  int return_horizon{};
  // The backbone's pieces beyond DDPG's (optional keys; their neutral values are the paper's
  // five's backbone, and rlpd-sac and td3-bc set theirs through their recipes, algos/registry.cpp).
  int utd_ratio{};          // learning steps per decision (RLPD's update-to-data ratio)
  int critic_ensemble{};    // N critics
  int critic_subset{};      // M ≤ N target critics drawn per update; the target is their minimum
  int policy_delay{};       // TD3: the actor and the targets move once per this many critic steps
  float target_noise{};     // TD3: std of the Gaussian noise on the target action (0: none)
  float target_noise_clip{};  // TD3: that noise clipped to ±this
  float init_temperature{};   // SAC: the entropy temperature α at the start
  float target_entropy_per_dim{};  // SAC: the target entropy is this × the action dimension
  float temperature_lr{};     // SAC: Adam's learning rate for log α
  // How the networks are built and start (optional keys every algorithm reads; neutral values are
  // the paper's five's, and a published baseline's recipe sets its code's): LayerNorm after each
  // hidden layer of the critics, and the initialisation scheme of every network (core/mlp.hpp).
  bool critic_layer_norm{};
  WeightInit init{};
};

}  // namespace rapid
