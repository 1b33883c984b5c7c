#include "algos/registry.hpp"

#include <algorithm>
#include <stdexcept>

#include "algos/col_all.hpp"
#include "algos/col_prior.hpp"
#include "algos/q_filter.hpp"
#include "algos/rapid_rl.hpp"
#include "algos/rapid_rl_return.hpp"
#include "algos/rlpd_sac.hpp"
#include "algos/td3_bc.hpp"
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
      // name       display      colour     prior  the actor loss's imitation weights  own keys
      {kRapidRl, "RAPID-RL", "tab:red", true, make<RapidRl>, {"epsilon", "bc_q_alpha"}},
      // RLPD as the paper uses it: the backbone on symmetric batches, no imitation term.
      {"rlpd", "RLPD", "tab:blue", true, make<ActorCritic>, {}},
      {"col-prior", "CoL-prior", "tab:green", true, make<ColPrior>, {"lambda_bc", "bc_q_alpha"}},
      {"col-all", "CoL-all", "tab:purple", true, make<ColAll>, {"lambda_bc", "bc_q_alpha"}},
      {"ddpg", "DDPG", "tab:gray", false, make<ActorCritic>, {}},
      // Not in the paper: RAPID-RL weighting by the mean reward over the next decisions.
      {"rapid-rl-return", "RAPID-RL (return)", "tab:orange", true, make<RapidRlReturn>, {"epsilon", "return_horizon", "bc_q_alpha"},
       /*uses_returns=*/true, /*in_paper=*/false, /*variant=*/true},
      // Not in the paper: RLPD as published (SAC, an ensemble of 10 critics, UTD 20; rlpd_sac.hpp).
      {"rlpd-sac", "RLPD (SAC)", "tab:cyan", true, make<RlpdSac>,
       {"utd_ratio", "critic_ensemble", "critic_subset", "init_temperature", "target_entropy_per_dim", "temperature_lr"},
       /*uses_returns=*/false, /*in_paper=*/false, /*variant=*/false,
       {{"utd_ratio", 20}, {"critic_ensemble", 10}, {"critic_subset", 2}, {"init_temperature", 1},
        {"target_entropy_per_dim", -0.5}, {"temperature_lr", 3e-4}, {"critic_layer_norm", true}, {"init", "xavier"}}},
      // Not in the paper: TD3+BC online on symmetric batches (td3_bc.hpp).
      {"td3-bc", "TD3+BC", "tab:brown", true, make<Td3Bc>,
       {"critic_ensemble", "critic_subset", "policy_delay", "target_noise", "target_noise_clip", "bc_q_alpha"},
       /*uses_returns=*/false, /*in_paper=*/false, /*variant=*/false,
       {{"critic_ensemble", 2}, {"critic_subset", 2}, {"policy_delay", 2}, {"target_noise", 0.2},
        {"target_noise_clip", 0.5}, {"bc_q_alpha", 2.5}, {"critic_layer_norm", false}, {"init", "pytorch"}}},
      // Not in the paper: CoL-prior's imitation kept where Q1(s, a) > Q1(s, π(s)) (q_filter.hpp).
      {"q-filter", "Q-filter", "tab:olive", true, make<QFilter>, {"lambda_bc", "bc_q_alpha"},
       /*uses_returns=*/false, /*in_paper=*/false, /*variant=*/false},
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

void Algorithm::check(const AgentConfig& config) const {
  return_window(config);
  try {
    check_critic_settings(config);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("algorithm '" + name + "': " + e.what());
  }
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
  throw std::invalid_argument("unknown algorithm '" + printable(name) + "'; expected one of " + comma_joined(algo_names()));
}

}  // namespace rapid
