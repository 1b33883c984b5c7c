// One engine for the claims: a claim (sweep/claim_spec.hpp) expanded over a summary into groups of
// comparisons. The point-mean check (claims.hpp) compares each comparison's means; the decided
// check (decisions.hpp) tests its per-seed values; both count the groups that hold against the
// claim's share. A grid's own claims go through the same expansion as the paper's.
#pragma once

#include <string>
#include <vector>

#include "experiments/report/summary.hpp"
#include "experiments/sweep/claim_spec.hpp"

namespace rapid {

// One thing compared: x against y, as the decided table names it (Comparison's labels).
struct PlannedComparison {
  std::string where, metric, x, y;
  ClaimMetric measure = ClaimMetric::kFinalReturn;  // of each side's cell, unless bc_loss
  bool bc_loss = false;  // bc_windows: the cell's prior BC loss (x) against its online one (y)
  std::string dataset;   // bc_windows: the window's dataset
  std::string y_algo;  // the algorithm behind y (bc_windows: the claim's)
  const CellSummary* x_cell = nullptr;  // nullptr: the grid has the cell's place but no cell
  const CellSummary* y_cell = nullptr;  // bc_windows: the same cell as x (prior against online)
  ComparisonOutcome wanted = ComparisonOutcome::kXBetter;
  std::string delta_scenario;  // whose δ the equivalence test uses; empty: none (BC losses)
  // bc_windows: the window's label ("all", "first 20%") and its logged-step range [from, to].
  std::string window;
  double from = 0.0, to = -1.0;
};

// Comparisons that hold together: a row, a scenario, or a claim's windows.
struct PlannedGroup {
  std::string label;                     // "merge / initial", "merge"
  const CellSummary* subject = nullptr;  // most_rows: the claim's algorithm's cell in the row
  std::vector<PlannedComparison> comparisons;
};

struct ClaimPlan {
  const ClaimSpec* spec = nullptr;
  std::string not_applicable;  // why the grid cannot check it; empty when it can
  std::vector<PlannedGroup> groups;
  int needed = 0;  // groups that must hold
};

// Every claim of `s` (the paper's, then the grid's), expanded. A grid with axes gets its claims with
// no groups (the callers say why: the claims are about Table I's rows).
std::vector<ClaimPlan> plan_claims(const Summary& s);

// Groups that must hold out of `total` under the claim's share (most_rows: ⌈share · total⌉; the
// other kinds: all).
int groups_needed(const ClaimSpec& spec, int total);

}  // namespace rapid
