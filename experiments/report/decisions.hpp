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

namespace rapid {

// The profile's settings; nullopt when it has no decisions.json. Throws std::invalid_argument
// naming the file and field when the file is malformed.
std::optional<DecisionSettings> load_decision_settings(const std::string& profile);

// Decides the claims of `s` (its cells' per-seed finals, curves and BC losses). Claims whose data
// the grid lacks are N/A, as in check_claims.
Decisions decide_claims(const Summary& s, const DecisionSettings& settings);

}  // namespace rapid
