// Synthetic replay data for the update and training benchmarks: the speed of an update does not
// depend on what the numbers mean, only on their shapes (and on staying finite).
#pragma once

#include <cstdint>

#include "core/replay_buffer.hpp"

namespace rapid::bench {

// `n` random transitions: observations and actions uniform in [-1, 1], rewards uniform in
// [ε − 1, ε + 1] (so RAPID-RL imitates about half of them), one in twenty terminal; Batch::ret
// over `return_window` decisions.
ReplayBuffer synthetic_replay(int obs_dim, int act_dim, int n, float epsilon, std::uint64_t seed,
                              int return_window = 1);

}  // namespace rapid::bench
