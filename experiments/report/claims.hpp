// The paper's claims (C1–C6, docs/reports.md §claims.md) checked against a sweep's summary. Each check says PASS or
// FAIL with the numbers behind it, or N/A when the grid lacks what the claim is about (an
// algorithm, a dataset, the merge scenario). A cell the grid has but whose seeds all failed or
// are missing counts against the claim: no data is not evidence for it.
//
// Definitions (also written into claims.md):
//   C1 RAPID-RL has the highest mean final return in ≥ 2/3 of the scenario × dataset rows.
//   C2 RAPID-RL's mean beats DDPG's in every row (the initial dataset included).
//   C3 CoL-all's mean is below DDPG's in every row.
//   C4 CoL-prior's mean with `initial` is below its mean with `final+medium` in every scenario.
//   C5 RAPID-RL has the largest area under the mean evaluation curve (trapezoid over target_step
//      divided by the step range) in ≥ 2/3 of the rows.
//   C6 merge, RAPID-RL: with final+medium the prior BC loss averaged over the logged steps is
//      below the online one; with initial the prior loss is below the online one on average over
//      the first 20% of the logged step range and above it over the last 20%.
#pragma once

#include <vector>

#include "experiments/report/summary.hpp"

namespace rapid {

std::vector<ClaimResult> check_claims(const Summary& summary);

// The point-mean result of claim `id` in summary.claims, or nullptr.
const ClaimResult* point_mean_claim(const Summary& summary, const std::string& id);

}  // namespace rapid
