#include "experiments/report/claim_plan.hpp"

#include <algorithm>

#include "algos/registry.hpp"
#include "core/contains.hpp"
#include "experiments/report/format.hpp"
#include "experiments/run/dataset_build.hpp"

namespace rapid {

namespace {

std::string row_label(const TableRow& row) { return row.scenario + " / " + row.dataset; }

bool row_wanted(const ClaimSpec& spec, const TableRow& row) {
  return (spec.datasets.empty() || contains(spec.datasets, row.dataset)) &&
         (spec.scenarios.empty() || contains(spec.scenarios, row.scenario));
}

bool compared_against(const ClaimSpec& spec, const std::string& algo) {
  return spec.against.empty() ? is_paper_baseline(algo) : contains(spec.against, algo) && algo != spec.algo;
}

// What the grid lacks for the claim, in the order scenario, algorithms, datasets; empty if nothing.
std::string missing(const ClaimSpec& spec, const Summary& s) {
  for (const std::string& scenario : spec.named_scenarios())
    if (!contains(s.grid.scenarios, scenario)) return "the grid has no " + scenario + " scenario";
  for (const std::string& algo : {spec.algo, spec.other})
    if (!algo.empty() && !contains(s.grid.algos, algo)) return "the grid has no " + algo;
  if (spec.kind == ClaimKind::kMostRows &&
      std::none_of(s.grid.algos.begin(), s.grid.algos.end(), [&](const std::string& a) { return compared_against(spec, a); }))
    return "the grid has no other algorithm to compare with";
  // In the harness's dataset order (initial before final+medium), whatever order the claim names them.
  std::vector<std::string> datasets = spec.named_datasets();
  const auto rank = [](const std::string& d) {
    const auto& known = dataset_names();
    return std::find(known.begin(), known.end(), d) - known.begin();
  };
  std::stable_sort(datasets.begin(), datasets.end(), [&](const auto& a, const auto& b) { return rank(a) < rank(b); });
  for (const std::string& d : datasets)
    if (!contains(s.grid.datasets, d)) return "the grid has no " + d + " dataset";
  return "";
}

PlannedComparison two_cells(std::string where, const ClaimSpec& spec, std::string x,
                            const CellSummary* x_cell, std::string y_algo, std::string y, const CellSummary* y_cell,
                            std::string delta_scenario) {
  PlannedComparison c;
  c.where = std::move(where);
  c.metric = claim_metric_name(spec.metric);
  c.measure = spec.metric;
  c.x = std::move(x);
  c.x_cell = x_cell;
  c.y_algo = std::move(y_algo);
  c.y = std::move(y);
  c.y_cell = y_cell;
  c.delta_scenario = std::move(delta_scenario);
  return c;
}

std::string percent_text(double fraction) { return short_number(fraction * 100.0); }

void plan_rows(const ClaimSpec& spec, const Summary& s, ClaimPlan& plan) {
  for (const TableRow& row : s.rows) {
    if (!row_wanted(spec, row)) continue;
    PlannedGroup g;
    g.label = row_label(row);
    g.subject = s.column_cell(row, spec.algo);
    if (spec.kind == ClaimKind::kMostRows) {
      for (const auto& [algo, index] : row.cells)
        if (compared_against(spec, algo))
          g.comparisons.push_back(two_cells(g.label, spec, algo_display_name(spec.algo), g.subject, algo,
                                            algo_display_name(algo), &s.cells[index], row.scenario));
    } else {
      PlannedComparison c = two_cells(g.label, spec, algo_display_name(spec.algo), g.subject, spec.other,
                                      algo_display_name(spec.other), s.column_cell(row, spec.other), row.scenario);
      c.wanted = spec.above ? ComparisonOutcome::kXBetter : ComparisonOutcome::kYBetter;
      g.comparisons.push_back(std::move(c));
    }
    plan.groups.push_back(std::move(g));
  }
}

void plan_dataset_order(const ClaimSpec& spec, const Summary& s, ClaimPlan& plan) {
  const std::string name = algo_display_name(spec.algo);
  for (const std::string& scenario : s.grid.scenarios) {
    if (!spec.scenarios.empty() && !contains(spec.scenarios, scenario)) continue;
    PlannedGroup g;
    g.label = scenario;
    g.comparisons.push_back(two_cells(scenario, spec, name + " " + dataset_display_name(spec.above_dataset),
                                      s.find(scenario, spec.above_dataset, spec.algo), spec.algo,
                                      name + " " + dataset_display_name(spec.below), s.find(scenario, spec.below, spec.algo),
                                      scenario));
    plan.groups.push_back(std::move(g));
  }
}

void plan_bc_windows(const ClaimSpec& spec, const Summary& s, ClaimPlan& plan) {
  PlannedGroup g;
  g.label = spec.scenario;
  for (const BcWindowSpec& w : spec.windows) {
    PlannedComparison c;
    const CellSummary* cell = s.find(spec.scenario, w.dataset, spec.algo);
    // The window within the cell's logged steps (none when it logged no BC loss).
    double first = 0.0, last = -1.0;
    if (cell && !cell->bc_prior.empty()) {
      first = cell->bc_prior.step.front();
      last = cell->bc_prior.step.back();
    }
    const double part = (last - first) * w.fraction;
    std::string steps;
    switch (w.part) {
      case BcWindowSpec::Part::kAll:
        c.from = first, c.to = last, c.window = "all", steps = "all steps";
        break;
      case BcWindowSpec::Part::kFirst:
        c.from = first, c.to = first + part, c.window = "first " + percent_text(w.fraction) + "%";
        steps = "first " + percent_text(w.fraction) + " % of steps";
        break;
      case BcWindowSpec::Part::kLast:
        c.from = last - part, c.to = last, c.window = "last " + percent_text(w.fraction) + "%";
        steps = "last " + percent_text(w.fraction) + " % of steps";
        break;
    }
    c.where = spec.scenario + " / " + w.dataset + ", " + steps;
    c.metric = "BC loss";
    c.bc_loss = true;
    c.dataset = w.dataset;
    c.x = "prior";
    c.y = "online";
    c.y_algo = spec.algo;
    c.x_cell = c.y_cell = cell;
    // The larger loss is the "better" side of the test: prior below online is y better.
    c.wanted = w.prior_below ? ComparisonOutcome::kYBetter : ComparisonOutcome::kXBetter;
    g.comparisons.push_back(std::move(c));
  }
  plan.groups.push_back(std::move(g));
}

}  // namespace

int groups_needed(const ClaimSpec& spec, int total) {
  if (spec.kind != ClaimKind::kMostRows) return total;
  return (spec.share_numerator * total + spec.share_denominator - 1) / spec.share_denominator;
}

std::vector<ClaimPlan> plan_claims(const Summary& s) {
  std::vector<const ClaimSpec*> specs;
  for (const ClaimSpec& c : paper_claims()) specs.push_back(&c);
  for (const ClaimSpec& c : s.grid.claims) specs.push_back(&c);
  std::vector<ClaimPlan> plans;
  for (const ClaimSpec* spec : specs) {
    ClaimPlan p;
    p.spec = spec;
    if (!s.grid.axes.empty()) {
      plans.push_back(std::move(p));
      continue;
    }
    p.not_applicable = missing(*spec, s);
    if (p.not_applicable.empty()) switch (spec->kind) {
        case ClaimKind::kMostRows:
        case ClaimKind::kEveryRow: plan_rows(*spec, s, p); break;
        case ClaimKind::kDatasetOrder: plan_dataset_order(*spec, s, p); break;
        case ClaimKind::kBcWindows: plan_bc_windows(*spec, s, p); break;
      }
    p.needed = groups_needed(*spec, static_cast<int>(p.groups.size()));
    plans.push_back(std::move(p));
  }
  return plans;
}

}  // namespace rapid
