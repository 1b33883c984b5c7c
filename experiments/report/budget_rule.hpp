// The flow profile's budget rule (docs/datasets.md): from the reference DDPG's evaluation curves
// alone, the step T at which it has closed a fixed fraction of the gap between its untrained and
// its fully trained return. The table's cells train for T decisions; the prior datasets come from
// the reference's actor at T/10, T/2 and the end of its long run.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace rapid {

// One reference run's evaluation curve: (step, mean return) at t = 0, E, 2E, …, L.
struct ReferenceCurve {
  std::string label;  // e.g. "seed1000"
  std::vector<long> steps;
  std::vector<double> returns;
};

struct BudgetRuleOptions {
  double fraction = 0.6;        // of the gap P − R0 that T must close
  int smoothing = 3;            // evaluations in the trailing moving average s(t)
  double plateau_tolerance = 0.1;  // |third-quarter mean − P| ≤ this · (P − R0)
};

struct BudgetRuleResult {
  std::vector<long> steps;      // t
  std::vector<double> mean;     // c(t): mean over the runs
  std::vector<double> smoothed; // s(t)
  double r0 = 0.0;              // c(0)
  double plateau = 0.0;         // P: mean of c over t ≥ 3L/4
  double third_quarter = 0.0;   // mean of c over L/2 ≤ t < 3L/4
  bool plateaued = false;       // the plateau check passed
  double plateau_band = 0.0;    // plateau_tolerance · (P − R0): how far the third quarter may lie from P
  double fraction = 0.0;        // the options' fraction, for the report
  double threshold = 0.0;       // R0 + fraction · (P − R0)
  long budget = -1;             // T; −1 when s(t) never reaches the threshold
  long long_run = 0;            // L
};

// Applies the rule. Throws std::invalid_argument when the curves do not share one evaluation
// schedule starting at step 0, when there are none, or when P ≤ R0 (the reference did not learn:
// no fraction of a gap that does not exist is a budget).
BudgetRuleResult apply_budget_rule(const std::vector<ReferenceCurve>& curves, const BudgetRuleOptions& options = {});

// The reference curves under `dir`, by scenario: every ok DDPG record.json below it (a sweep
// folder, or a folder of `rapid run` outputs), labelled by its path. Throws
// std::invalid_argument when `dir` is not a folder, holds no such record, or holds a record that
// cannot be read.
std::map<std::string, std::vector<ReferenceCurve>> read_reference_curves(const std::string& dir);

// The rule's verdict as text: the numbers, the plateau check and T (or what to do instead).
std::string budget_rule_report(const std::string& scenario, const std::vector<ReferenceCurve>& curves,
                               const BudgetRuleResult& r);

}  // namespace rapid
