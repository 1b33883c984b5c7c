#include "algos/registry.hpp"

#include <algorithm>
#include <stdexcept>

#include "algos/col_all.hpp"
#include "algos/col_prior.hpp"
#include "algos/rapid_rl.hpp"
#include "algos/rapid_rl_return.hpp"
#include "core/printable.hpp"

namespace rapid {

namespace {
template <typename Agent>
std::unique_ptr<ActorCritic> make(int obs_dim, int act_dim, const AgentConfig& config, std::uint64_t init_seed) {
  return std::make_unique<Agent>(obs_dim, act_dim, config, init_seed);
}
}  // namespace

const std::vector<Algorithm>& algorithms() {
  static const std::vector<Algorithm> table = {
      // name       display      prior  the actor loss's imitation weights  own keys
      {"rapid-rl", "RAPID-RL", true, make<RapidRl>, {"epsilon", "bc_q_alpha"}},
      // RLPD as the paper uses it: the backbone on symmetric batches, no imitation term.
      {"rlpd", "RLPD", true, make<ActorCritic>, {}},
      {"col-prior", "CoL-prior", true, make<ColPrior>, {"lambda_bc", "bc_q_alpha"}},
      {"col-all", "CoL-all", true, make<ColAll>, {"lambda_bc", "bc_q_alpha"}},
      {"ddpg", "DDPG", false, make<ActorCritic>, {}},
      // Not in the paper: RAPID-RL weighting by the mean reward over the next decisions.
      {"rapid-rl-return", "RAPID-RL (return)", true, make<RapidRlReturn>, {"epsilon", "return_horizon", "bc_q_alpha"},
       /*uses_returns=*/true, /*in_paper=*/false},
  };
  return table;
}

bool Algorithm::reads(const std::string& key) const {
  if (std::find(own_keys.begin(), own_keys.end(), key) != own_keys.end()) return true;
  return !is_algorithm_key(key);
}

int Algorithm::return_window(const AgentConfig& config) const {
  if (!uses_returns) return 1;
  if (config.return_horizon < 1)
    throw std::invalid_argument("algorithm '" + name +
                                "' needs config key 'return_horizon' (decisions of the return window; e.g. --set "
                                "return_horizon=20)");
  return config.return_horizon;
}

bool is_algorithm_key(const std::string& key) {
  for (const Algorithm& a : algorithms())
    if (std::find(a.own_keys.begin(), a.own_keys.end(), key) != a.own_keys.end()) return true;
  return false;
}

std::vector<std::string> algo_names() {
  std::vector<std::string> names;
  for (const Algorithm& a : algorithms()) names.push_back(a.name);
  return names;
}

const Algorithm& find_algorithm(const std::string& name) {
  for (const Algorithm& a : algorithms())
    if (a.name == name) return a;
  std::string known;
  for (const Algorithm& a : algorithms()) known += (known.empty() ? "" : ", ") + a.name;
  throw std::invalid_argument("unknown algorithm '" + printable(name) + "'; expected one of " + known);
}

}  // namespace rapid
