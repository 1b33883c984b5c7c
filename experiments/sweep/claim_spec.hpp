// A claim as data: what it compares, on which rows, and how many must hold. The paper's C1–C6 are
// declared once in experiments/claims/paper.json (embedded at build time); a grid may declare its
// own under "claims" in the same form (docs/sweeps.md). report/claim_plan.hpp expands a claim over
// a sweep's summary; the point-mean check (report/claims.hpp) and the decided one
// (report/decisions.hpp) both read that expansion.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace rapid {

enum class ClaimKind {
  kMostRows,      // `algo`'s metric strictly the highest among `against` in ≥ share of the rows
  kEveryRow,      // `x`'s metric above (or below) `y`'s in every row
  kDatasetOrder,  // in every scenario, `algo` with dataset `below` under `algo` with `above`
  kBcWindows,     // `algo` in `scenario`: prior BC loss below (or above) the online one per window
};

enum class ClaimMetric { kFinalReturn, kCurveArea };

// A part of a cell's logged BC-loss steps: all of them, or the first or last fraction of the range.
struct BcWindowSpec {
  enum class Part { kAll, kFirst, kLast };
  std::string dataset;
  Part part = Part::kAll;
  double fraction = 1.0;     // kFirst / kLast: the share of the step range, in (0, 1]
  bool prior_below = true;   // the claim wants the prior loss below the online one (else above)
};

struct ClaimSpec {
  std::string id, statement, definition;
  ClaimKind kind = ClaimKind::kEveryRow;
  ClaimMetric metric = ClaimMetric::kFinalReturn;
  std::string algo;                   // most_rows, dataset_order, bc_windows; every_row: x
  std::string other;                  // every_row: y
  bool above = true;                  // every_row: x above y (else below)
  std::vector<std::string> against;   // most_rows: empty = the paper's baselines in the grid
  int share_numerator = 1, share_denominator = 1;  // most_rows
  std::string below, above_dataset;   // dataset_order: the two datasets
  std::string scenario;               // bc_windows
  std::vector<BcWindowSpec> windows;  // bc_windows
  std::vector<std::string> datasets, scenarios;  // rows the claim is about (empty: every row)

  // The algorithms, datasets and scenarios the claim names (the grid must have them).
  std::vector<std::string> named_algos() const;
  std::vector<std::string> named_datasets() const;
  std::vector<std::string> named_scenarios() const;
};

// What the kinds' fields are called in JSON, for messages.
std::string claim_kind_name(ClaimKind kind);
std::string claim_metric_name(ClaimMetric metric);  // "final return", "curve area"

// Reads one claim. Throws std::invalid_argument "FIELD: problem" (FIELD starts with `field`).
ClaimSpec parse_claim(const nlohmann::json& j, const std::string& field);

// The paper's claims, in the file's order (parsed once; a broken file is a build's bug:
// std::logic_error).
const std::vector<ClaimSpec>& paper_claims();

}  // namespace rapid
