// Baselines for `rapid diff` (docs/reports.md §Baselines and `rapid diff`): the per-cell numbers of a sweep, stored so CI can check a
// fresh sweep against them.
//
// Schema "rapid.baseline/1":
//   {"schema": "rapid.baseline/1", "grid": NAME,
//    "statistics": {"std": "population", "confidence": 0.95, "replicates": R},
//    "cells": [{"cell": "merge/initial/rapid-rl", "scenario", "dataset" (null for ddpg), "algo",
//               "n_ok", "n_expected", "mean", "std", "mean_ci": [lo, hi], "iqm", "iqm_ci",
//               "finals": [{"seed", "status", "final"}]}]}
// mean, std, iqm and the intervals are null for a cell without an ok seed.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "experiments/report/summary.hpp"

namespace rapid {

inline constexpr const char* kBaselineSchema = "rapid.baseline/1";

nlohmann::json make_baseline(const Summary& summary);

struct DiffOptions {
  double rtol = 1e-6;
  double atol = 1e-9;   // floor for values near zero
  bool stat = false;    // pass when the baseline mean lies in the new 95% interval of the mean
};

struct CellDifference {
  std::string cell;      // "merge/initial/rapid-rl"
  std::string baseline;  // "112.3 ± 4.1 (n=3/3)", "—" when the side lacks the cell
  std::string now;
  std::string why;
};

struct DiffResult {
  std::string schema_error;  // set when the baseline is not a rapid.baseline/1 document
  std::size_t cells_compared = 0;
  std::size_t cells = 0;  // in the sweep or the baseline: a cell only the baseline has counts too
  std::vector<CellDifference> differences;
  bool ok() const { return schema_error.empty() && differences.empty(); }
};

DiffResult diff_against_baseline(const Summary& summary, const nlohmann::json& baseline, const DiffOptions& options);

}  // namespace rapid
