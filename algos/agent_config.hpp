// Hyper-parameters of the actor-critic backbone. The values used by runs come from the
// per-scenario config files (experiments/configs/); docs/algorithms.md says why each was chosen.
#pragma once

#include <vector>

namespace rapid {

struct AgentConfig {
  std::vector<int> actor_hidden = {256, 256};
  std::vector<int> critic_hidden = {256, 256};
  float actor_lr = 3e-4f;
  float critic_lr = 3e-4f;
  float gamma = 0.99f;
  float tau = 0.005f;          // Polyak rate of the target networks
  int batch_size = 256;        // B; with a prior dataset B/2 prior + B/2 online
  float noise_std = 0.1f;      // Gaussian exploration noise on the [-1, 1] action
  float lambda_bc = 1.0f;      // CoL's BC weight (CoL uses 1.0 for every term)
  float epsilon = -0.15f;      // RAPID-RL's reward threshold ε
};

}  // namespace rapid
