#include "algos/registry.hpp"

#include <stdexcept>

#include "algos/col_all.hpp"
#include "algos/col_prior.hpp"
#include "algos/rapid_rl.hpp"
#include "algos/rlpd.hpp"

namespace rapid {

const std::vector<std::string>& algo_names() {
  static const std::vector<std::string> names = {"rapid-rl", "rlpd", "col-prior", "col-all", "ddpg"};
  return names;
}

std::unique_ptr<ActorCritic> make_agent(const std::string& name, int obs_dim, int act_dim,
                                        const AgentConfig& config, std::uint64_t init_seed) {
  if (name == "ddpg") return std::make_unique<ActorCritic>(obs_dim, act_dim, config, init_seed);
  if (name == "rlpd") return std::make_unique<Rlpd>(obs_dim, act_dim, config, init_seed);
  if (name == "col-prior") return std::make_unique<ColPrior>(obs_dim, act_dim, config, init_seed);
  if (name == "col-all") return std::make_unique<ColAll>(obs_dim, act_dim, config, init_seed);
  if (name == "rapid-rl") return std::make_unique<RapidRl>(obs_dim, act_dim, config, init_seed);
  std::string known;
  for (const auto& n : algo_names()) known += (known.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown algorithm '" + name + "'; expected one of " + known);
}

bool algo_uses_prior(const std::string& name) {
  return make_agent(name, 1, 1, AgentConfig{.actor_hidden = {1}, .critic_hidden = {1}}, 0)->uses_prior();
}

}  // namespace rapid
