// A search space file for `rapid tune` (docs/tuning.md §The space file): which config keys are
// searched over which ranges, the tuning seeds, the candidates per (scenario, algorithm), the
// successive-halving rungs, and the evaluation the trials run with. Committed before any trial, so
// the ranges and the objective cannot follow the results.
//
// Schema (JSON object; every key not listed is an error):
//   "name"          string of [A-Za-z0-9._-]
//   "description"   optional string
//   "seeds"         tuning seeds, distinct, each below 100 (seeds from 100 up are the rechecks'):
//                   unit u of a prior algorithm is seeds[u] on every dataset of the grid; of ddpg,
//                   which reads no dataset, seeds[u·D … u·D+D−1] (D datasets), so that every
//                   algorithm's unit is D runs
//   "candidates"    integer ≥ 1: candidates per (scenario, algorithm), the default among them (0)
//   "sampler_seed"  non-negative integer: candidate k ≥ 1 takes, for each key, the quantile
//                   u(k, key) of its range, the same for every algorithm and scenario
//   "rungs"         increasing positive integers: the units a surviving candidate has run after
//                   each rung; the better half (rounded up) goes on after each rung but the last
//   "trial_config"  optional object: schedule keys every trial's cells get (its evaluation), either
//                   one object for every scenario or {"scenario": {...}} per scenario
//   "keys"          object key → {"log_uniform" | "uniform": [lo, hi] or {"scenario": [lo, hi]},
//                   or "choice": [values…], and optionally "algos": [names]}: the range of a
//                   config key, the same for every algorithm that reads it (algos/registry.hpp),
//                   unless "algos" names who tunes it
//   "confirmation"  optional object: "alpha" (the one-sided test's level, default 0.05), "power"
//                   (default 0.8) and "delta" (a number, or {"scenario": number}: the improvement
//                   the confirmation's units are sized to detect; default each scenario's δ from
//                   the profile's decisions.json)
#pragma once

#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace rapid {

struct SpaceKey {
  std::string key;
  std::string kind;  // "log_uniform", "uniform" or "choice"
  std::map<std::string, std::pair<double, double>> ranges;  // scenario → [lo, hi]; "" for every scenario
  std::vector<nlohmann::json> choices;                      // kind "choice"
  std::vector<std::string> algos;                            // empty: every algorithm that reads the key
};

// The confirmation stage's settings (docs/tuning.md §Why a winner must be confirmed): the one-sided
// test's level, the power its units are sized for, and δ, the improvement worth adopting, per
// scenario (empty: each scenario's decision margin from the profile's decisions.json).
struct ConfirmationSettings {
  double alpha = 0.05, power = 0.8;
  std::map<std::string, double> delta;  // scenario → δ; "" → every scenario's
};

struct SearchSpace {
  std::string name, description;
  std::vector<std::uint64_t> seeds;
  int candidates = 0;
  std::uint64_t sampler_seed = 0;
  std::vector<int> rungs;  // cumulative units
  nlohmann::json trial_config = nlohmann::json::object();  // {"": {...}} or scenario → {...}
  std::vector<SpaceKey> keys;  // in key order
  ConfirmationSettings confirmation;  // "confirmation" (optional)
  nlohmann::json document;     // as read, for tuned.json
};

// The confirmation's fresh tuning seeds: 50-99 but the space's own and `excluded` (the grid's), in
// ascending order. A unit of a prior algorithm is one of them, of ddpg as many as the datasets.
std::vector<std::uint64_t> confirmation_seeds(const SearchSpace& space, const std::vector<std::uint64_t>& excluded);

// Reads and checks a space file's shape (unknown keys, ranges, rungs, seeds). Throws
// std::invalid_argument("space PATH: FIELD: problem").
SearchSpace load_space(const std::string& path);
SearchSpace parse_space(const nlohmann::json& document, const std::string& label);

// The seed numbers a candidate of `algo` runs in its units [0, units): uses_prior → seeds[u],
// else `datasets` seeds per unit.
std::vector<std::uint64_t> unit_seeds(const SearchSpace& space, bool uses_prior, int datasets, int units);

// The most units the rungs ask for, and the seeds that takes for an algorithm without a dataset.
int max_units(const SearchSpace& space);

// Candidate k's overrides for (scenario, algo): empty for k = 0 (the defaults); for k ≥ 1 every
// key of the space the algorithm tunes, at its common quantile u(k, key), rounded to 3
// significant digits (so folder names and grid.json stay short and exact).
nlohmann::json candidate_overrides(const SearchSpace& space, const std::string& scenario, const std::string& algo, int k);

// The trial schedule overrides of `scenario`.
nlohmann::json trial_overrides(const SearchSpace& space, const std::string& scenario);

// Candidates alive at each rung: n, ⌈n/2⌉, ⌈n/4⌉, … (one per rung).
std::vector<int> rung_sizes(const SearchSpace& space);

// Units one (scenario, algorithm) spends when every rung runs: Σ_i n_i · (rungs[i] − rungs[i−1]).
int units_per_search(const SearchSpace& space);

}  // namespace rapid
