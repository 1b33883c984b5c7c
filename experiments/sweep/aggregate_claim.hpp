// An aggregate claim (issue #66): one number per seed over many rows, so that a question the
// per-row tests cannot decide at any affordable number of seeds is asked once. For each seed, the
// mean over the grid's scenario × dataset rows of (x's final return − y's) / δ of the row's
// scenario, paired by seed; a one-sample t test for a difference and TOST within ±margin (δ units).
// docs/confirmatory.md registers six such claims for the confirmatory study
// (experiments/claims/confirmatory.json, embedded at build time); a grid may declare its own under
// "claims" with "kind": "aggregate" (docs/sweeps.md). report/decisions.hpp decides them.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace rapid {

struct AggregateClaimSpec {
  std::string id, statement;
  std::string x, y;     // algorithms: x − y
  double margin = 1.0;  // equivalence within ±margin, in δ units
  // The seeds the claim uses, inclusive; none: every seed of the grid.
  std::optional<std::uint64_t> first_seed, last_seed;
  bool registered = false;  // from a committed pre-registration (experiments/claims/), not the grid

  bool uses_seed(std::uint64_t seed) const {
    return (!first_seed || seed >= *first_seed) && (!last_seed || seed <= *last_seed);
  }
  // "seeds 200-239", "every seed"
  std::string seeds_text() const;
};

// Whether a grid's claim entry is an aggregate one ("kind": "aggregate").
bool is_aggregate_claim(const nlohmann::json& j);

// Reads one aggregate claim. Throws std::invalid_argument "FIELD: problem" (FIELD starts with `field`).
AggregateClaimSpec parse_aggregate_claim(const nlohmann::json& j, const std::string& field);

// The claims a committed pre-registration registers for the grid named `grid_name`, in the file's
// order; empty for any other grid. (A broken file is a build's bug: std::logic_error.)
std::vector<AggregateClaimSpec> registered_aggregate_claims(const std::string& grid_name);

}  // namespace rapid
