#include "algos/registry.hpp"

#include <algorithm>
#include <deque>
#include <iterator>
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
      // name       display      colour     prior  the agent              method keys it reads
      {kRapidRl, "RAPID-RL", "tab:red", true, make<RapidRl>, {&kEpsilon, &kBcQAlpha}},
      // RLPD as the paper uses it: the backbone on symmetric batches, no imitation term.
      {"rlpd", "RLPD", "tab:blue", true, make<ActorCritic>, {}},
      {"col-prior", "CoL-prior", "tab:green", true, make<ColPrior>, {&kLambdaBc, &kBcQAlpha}},
      {"col-all", "CoL-all", "tab:purple", true, make<ColAll>, {&kLambdaBc, &kBcQAlpha}},
      {"ddpg", "DDPG", "tab:gray", false, make<ActorCritic>, {}},
      // Not in the paper: RAPID-RL weighting by the mean reward over the next decisions.
      {"rapid-rl-return", "RAPID-RL (return)", "tab:orange", true, make<RapidRlReturn>,
       {&kEpsilon, &kReturnHorizon, &kBcQAlpha}, /*uses_returns=*/true, /*in_paper=*/false, /*variant=*/true},
      // Not in the paper: RLPD as published (SAC, an ensemble of 10 critics, UTD 20; rlpd_sac.hpp).
      {"rlpd-sac", "RLPD (SAC)", "tab:cyan", true, make<RlpdSac>,
       {&kUtdRatio, &kCriticEnsemble, &kCriticSubset, &kInitTemperature, &kTargetEntropyPerDim, &kTemperatureLr},
       /*uses_returns=*/false, /*in_paper=*/false, /*variant=*/false, rlpd_sac_recipe()},
      // Not in the paper: TD3+BC online on symmetric batches (td3_bc.hpp).
      {"td3-bc", "TD3+BC", "tab:brown", true, make<Td3Bc>,
       {&kCriticEnsemble, &kCriticSubset, &kPolicyDelay, &kTargetNoise, &kTargetNoiseClip, &kBcQAlpha},
       /*uses_returns=*/false, /*in_paper=*/false, /*variant=*/false, td3_bc_recipe()},
      // Not in the paper: CoL-prior's imitation kept where Q1(s, a) > Q1(s, π(s)) (q_filter.hpp).
      {"q-filter", "Q-filter", "tab:olive", true, make<QFilter>, {&kLambdaBc, &kBcQAlpha},
       /*uses_returns=*/false, /*in_paper=*/false, /*variant=*/false},
  };
  return table;
}

namespace {
bool lists(const std::vector<const MethodKey*>& keys, const std::string& name) {
  return std::any_of(keys.begin(), keys.end(), [&](const MethodKey* k) { return k->name == name; });
}
}  // namespace

bool Algorithm::reads(const std::string& key) const { return lists(keys, key) || !is_algorithm_key(key); }

int Algorithm::return_window(const AgentConfig& config) const {
  if (!uses_returns) return 1;
  const int horizon = config.method.integer(kReturnHorizon);
  if (horizon < 1)
    throw std::invalid_argument("algorithm '" + name +
                                "' needs config key 'return_horizon' (decisions of the return window; e.g. --set "
                                "return_horizon=20)");
  return horizon;
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
  return std::any_of(algorithms().begin(), algorithms().end(), [&](const Algorithm& a) { return lists(a.keys, key); });
}

std::vector<const MethodKey*> method_keys() {
  std::vector<const MethodKey*> keys;
  for (const Algorithm& a : algorithms())
    for (const MethodKey* k : a.keys)
      if (!lists(keys, k->name)) keys.push_back(k);
  return keys;
}

std::vector<std::string> algo_names() {
  std::vector<std::string> names;
  for (const Algorithm& a : algorithms()) names.push_back(a.name);
  return names;
}

namespace {
// A deque: registering one more row leaves the references to the others valid.
std::deque<Algorithm>& external_rows() {
  static std::deque<Algorithm> rows;
  return rows;
}
// Colours none of the table's rows has, given out in registration order.
const char* const kExternalColours[] = {"tab:pink", "black", "gold", "navy", "teal", "magenta", "lime", "maroon"};
}  // namespace

const Algorithm& register_external_algorithm(const std::string& name, bool uses_prior,
                                             std::vector<const MethodKey*> keys) {
  for (const Algorithm& a : algorithms())
    if (a.name == name) throw std::invalid_argument("'" + name + "' is the harness's own algorithm; give the method a name of its own");
  std::deque<Algorithm>& rows = external_rows();
  auto it = std::find_if(rows.begin(), rows.end(), [&](const Algorithm& a) { return a.name == name; });
  if (it == rows.end()) {
    rows.emplace_back();
    it = std::prev(rows.end());
    it->colour = kExternalColours[(rows.size() - 1) % std::size(kExternalColours)];
  }
  it->name = name;
  it->display_name = name;
  it->uses_prior = uses_prior;
  it->keys = std::move(keys);
  it->in_paper = false;
  return *it;
}

const Algorithm* lookup_algorithm(const std::string& name) {
  for (const Algorithm& a : algorithms())
    if (a.name == name) return &a;
  for (const Algorithm& a : external_rows())
    if (a.name == name) return &a;
  return nullptr;
}

const Algorithm& find_algorithm(const std::string& name) {
  if (const Algorithm* a = lookup_algorithm(name)) return *a;
  std::vector<std::string> names = algo_names();
  for (const Algorithm& a : external_rows()) names.push_back(a.name);
  throw std::invalid_argument("unknown algorithm '" + printable(name) + "'; expected one of " + comma_joined(names));
}

std::vector<std::string> names_in_table_order(const std::vector<std::string>& names) {
  std::vector<std::string> out;
  for (const Algorithm* a : rows_in_table_order(names)) out.push_back(a->name);
  return out;
}

std::vector<const Algorithm*> rows_in_table_order(const std::vector<std::string>& names) {
  std::vector<const Algorithm*> rows;
  for (const Algorithm& a : algorithms())
    if (std::find(names.begin(), names.end(), a.name) != names.end()) rows.push_back(&a);
  for (const std::string& name : names)
    if (const Algorithm* a = lookup_algorithm(name); a != nullptr && a->make == nullptr) rows.push_back(a);
  return rows;
}

}  // namespace rapid
