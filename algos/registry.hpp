// The name → algorithm table behind `--algo`.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "algos/actor_critic.hpp"

namespace rapid {

// In the order of the paper's Table I columns.
const std::vector<std::string>& algo_names();
bool algo_uses_prior(const std::string& name);
// Throws std::invalid_argument("unknown algorithm '…'; expected one of …").
std::unique_ptr<ActorCritic> make_agent(const std::string& name, int obs_dim, int act_dim,
                                        const AgentConfig& config, std::uint64_t init_seed);

}  // namespace rapid
