// The algorithms, one row each. Every list of algorithm names, every help text and every report
// reads this table, so adding an algorithm is one header (its imitation weights, or its update
// rule, with the keys it declares) and one row.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "algos/actor_critic.hpp"

namespace rapid {

// The method the paper proposes: every report compares the other algorithms with it.
inline const std::string kRapidRl = "rapid-rl";

struct Algorithm {
  std::string name;          // --algo, grids, run records, report keys
  std::string display_name;  // tables and figures, as the paper prints it
  std::string colour;        // its lines in every figure (a matplotlib colour; summary.json carries it to scripts/plot)
  // Every batch is B/2 from the prior dataset and B/2 online (symmetric sampling), so a run needs
  // a dataset; otherwise the whole batch is online and a run takes no dataset.
  bool uses_prior = false;
  std::unique_ptr<ActorCritic> (*make)(int obs_dim, int act_dim, const AgentConfig& config,
                                       std::uint64_t init_seed) = nullptr;
  // The method keys it reads (ε, λ_BC, …; algos/method_key.hpp), declared in the files of the code
  // that reads them. A method key is read by the algorithms that list it only; every other config
  // key is read by all of them. Sweeps rely on it: a grid axis over such a key does not duplicate
  // the jobs of the algorithms that ignore it (tests/test_algos.cpp checks that changing the key
  // leaves their updates unchanged).
  std::vector<const MethodKey*> keys;
  // Its imitation weights read Batch::ret, each transition's mean reward over the next
  // `return_horizon` decisions of its episode: a run builds its buffers with that window, and
  // needs the key and a prior dataset made of episodes.
  bool uses_returns = false;
  // One of the paper's five algorithms (Table I's columns): the claims check and the probability
  // that RAPID-RL beats each baseline concern these only.
  bool in_paper = true;
  // A variant of RAPID-RL itself (an ablation such as rapid-rl-return): the reports ask whether it
  // beats RAPID-RL. Every other algorithm is a baseline, and they ask whether RAPID-RL beats it.
  bool variant = false;
  // The published values of the method's keys (RLPD's UTD, ensemble and temperature, TD3's delay
  // and noise, each code base's critic LayerNorm and initialisation), given to a run whose config
  // leaves the key out (experiments/run/job.hpp, with_recipe): the run's record lists the keys
  // they filled. A config that gives the key wins. Written beside the algorithm with its sources.
  Recipe recipe = {};

  bool reads(const std::string& key) const;
  // The window its buffers compute Batch::ret over: return_horizon for an algorithm that uses
  // returns, 1 (ret = r, at no cost) for the others. Throws std::invalid_argument("algorithm 'A'
  // needs config key 'return_horizon' (…)") when the key was not given.
  int return_window(const AgentConfig& config) const;
  // Throws std::invalid_argument naming the key when `config` (its recipe applied) cannot make
  // this algorithm's agent: a missing return_horizon, a critic subset larger than the ensemble.
  void check(const AgentConfig& config) const;
};

// In the order of the paper's Table I columns, then the algorithms the paper does not have.
const std::vector<Algorithm>& algorithms();
std::vector<std::string> algo_names();

// A method outside the harness (a command a grid names, experiments/run/external_method.hpp) as
// a row: its name, whether it uses prior data, no agent (`make` is null) and the method keys it
// says it reads (ε, λ_BC, …: then axes, algo_config and tuning vary them for it), besides every
// shared key. Registered when a grid that names it is loaded; registering a name again
// replaces the row (rows stay where they are: find_algorithm's references remain valid). Throws
// std::invalid_argument when the name is one of algorithms()'.
const Algorithm& register_external_algorithm(const std::string& name, bool uses_prior,
                                             std::vector<const MethodKey*> keys = {});
// The row find_algorithm would return, or null: the table's, then the registered external ones.
const Algorithm* lookup_algorithm(const std::string& name);
// The rows of `names`: the table's in its order, then the others (external methods) in the order given.
std::vector<const Algorithm*> rows_in_table_order(const std::vector<std::string>& names);
// Their names in that order: a table's columns.
std::vector<std::string> names_in_table_order(const std::vector<std::string>& names);

// Whether some algorithm lists `key` among its method keys (then the others ignore it).
bool is_algorithm_key(const std::string& key);

// Every algorithm's method keys, each once, in the order the rows first list them: the run
// config's key table has a row for each.
std::vector<const MethodKey*> method_keys();

// Throws std::invalid_argument("unknown algorithm '…'; expected one of …").
const Algorithm& find_algorithm(const std::string& name);

}  // namespace rapid
