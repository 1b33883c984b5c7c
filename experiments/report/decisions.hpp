// Decided claims (docs/decisions.md): each claim's comparisons decided by Welch / TOST tests under
// Holm's family-wise control, and the claim CONFIRMED, REFUTED or UNDECIDED from them, with the
// seeds an undecided comparison would need. Beside, not instead of, the point-mean verdicts of
// claims.hpp.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "experiments/report/summary.hpp"
#include "experiments/sweep/aggregate_claim.hpp"

namespace rapid {

// The profile's settings; nullopt when it has no decisions.json. Throws std::invalid_argument
// naming the file and field when the file is malformed.
std::optional<DecisionSettings> load_decision_settings(const std::string& profile);

// Decides the claims of `s` (its cells' per-seed finals, curves and BC losses). Claims whose data
// the grid lacks are N/A, as in check_claims. Comparisons in `frozen` (adaptive seeds' earlier
// looks, report/decide_looks.hpp) keep their outcome from then, in the family with p 0 or 1.
Decisions decide_claims(const Summary& s, const DecisionSettings& settings, const FrozenComparisons& frozen = {});

// A claim's verdict from its groups of comparisons (indices into `comparisons`, each decided):
// CONFIRMED when at least `needed` groups hold as decided, REFUTED when fewer than `needed` still
// could, else UNDECIDED; N/A with `not_applicable` as the reason when that is not empty.
DecidedClaim decided_verdict(const std::string& id, const std::string& not_applicable,
                             const std::vector<std::vector<std::size_t>>& groups, int needed,
                             const std::vector<Comparison>& comparisons);

// The grid's baselines that the paper does not run (registry: not in the paper, not a variant of
// RAPID-RL; rlpd-sac and td3-bc), in the grid's order.
std::vector<std::string> published_baselines(const Summary& s);

// RAPID-RL against each of them in every row, on final return, by the same tests as the claims but
// as a Holm family of its own (its comparisons only; no claim verdicts), so that adding such a
// baseline to a grid leaves the claims' verdicts as they were. nullopt when the grid has none of
// them, no rapid-rl, or axes.
std::optional<Decisions> decide_published_baselines(const Summary& s, const DecisionSettings& settings);

// The aggregate claims that apply to `s`: those a committed pre-registration registers for its grid
// (experiments/claims/confirmatory.json), then the grid's own (sweep/aggregate_claim.hpp).
std::vector<AggregateClaimSpec> aggregate_claims_of(const Summary& s);

// Those claims decided, one paired comparison each (x − y per seed, in δ units; a one-sample t test
// for a difference, TOST within ±margin), all of them one Holm family of their own at α, apart from
// the paper's claims and the published baselines (docs/confirmatory.md). nullopt when none apply.
std::optional<Decisions> decide_aggregate_claims(const Summary& s, const DecisionSettings& settings);

// Per published baseline (display name, in the grid's order), how many rows each outcome of RAPID-RL
// against it took in s.baseline_decisions; empty without them.
struct BaselineTally {
  std::string name;
  int rows = 0, rapid_rl_higher = 0, baseline_higher = 0, equivalent = 0, undecided = 0;
};
std::vector<BaselineTally> tally_published_baselines(const Summary& s);

}  // namespace rapid
