// The point-mean check of the claims (docs/reports.md §claims.md): the paper's C1–C6 as declared in
// experiments/claims/paper.json and the grid's own, each expanded by claim_plan.hpp and judged on
// the cells' means (seed-mean curves for the BC windows). PASS or FAIL with the numbers behind it,
// or N/A when the grid lacks what the claim is about (an algorithm, a dataset, a scenario). A cell
// the grid has but whose seeds all failed or are missing counts against the claim: no data is not
// evidence for it. decisions.hpp decides the same comparisons by tests.
#pragma once

#include <vector>

#include "experiments/report/summary.hpp"

namespace rapid {

std::vector<ClaimResult> check_claims(const Summary& summary);

// The point-mean result of claim `id` in summary.claims, or nullptr.
const ClaimResult* point_mean_claim(const Summary& summary, const std::string& id);

}  // namespace rapid
