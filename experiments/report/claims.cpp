#include "experiments/report/claims.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>

#include "experiments/report/claim_plan.hpp"
#include "experiments/report/format.hpp"

namespace rapid {

namespace {

ClaimResult claim(std::string id, std::string statement, std::string definition) {
  ClaimResult c;
  c.id = std::move(id);
  c.statement = std::move(statement);
  c.definition = std::move(definition);
  return c;
}

ClaimResult not_applicable(ClaimResult c, std::string why) {
  c.verdict = "N/A";
  c.reason = std::move(why);
  return c;
}

std::string count_text(int wins, int total) { return std::to_string(wins) + "/" + std::to_string(total); }

// A cell's point estimate of the claim's metric: its mean final return, or its mean curve's area.
std::optional<double> point(ClaimMetric metric, const CellSummary* cell) {
  if (!cell) return std::nullopt;
  return metric == ClaimMetric::kFinalReturn ? cell->mean : cell->eval_auc;
}

std::string score_name(ClaimMetric metric) { return metric == ClaimMetric::kFinalReturn ? "mean" : "curve area"; }

std::string yes_no(bool ok, bool have_data) { return ok ? "yes" : (have_data ? "no" : "no (no data)"); }

// most_rows: per row, the claim's algorithm against the best of the others it is compared with.
ClaimResult most_rows_best(const ClaimPlan& p, ClaimResult c) {
  const ClaimSpec& spec = *p.spec;
  const std::string name = algo_display_name(spec.algo), score = score_name(spec.metric);
  c.header = {"scenario / dataset", name + " " + score, "best other", name + " highest"};
  int wins = 0;
  for (const PlannedGroup& g : p.groups) {
    const std::optional<double> ours = point(spec.metric, g.subject);
    std::optional<double> best_other;
    std::string best_other_algo;
    for (const PlannedComparison& cmp : g.comparisons)
      if (const std::optional<double> v = point(cmp.measure, cmp.y_cell); v && (!best_other || *v > *best_other)) {
        best_other = v;
        best_other_algo = cmp.y_algo;
      }
    const bool won = ours && (!best_other || *ours > *best_other);
    wins += won;
    c.rows.push_back({g.label, short_number(ours),
                      best_other ? algo_display_name(best_other_algo) + " " + short_number(best_other) : "—",
                      yes_no(won, ours.has_value())});
  }
  const int total = static_cast<int>(p.groups.size());
  c.verdict = wins >= p.needed && total > 0 ? "PASS" : "FAIL";
  const std::string share = spec.share_numerator == spec.share_denominator
                                ? "all"
                                : "≥ " + std::to_string(spec.share_numerator) + "/" + std::to_string(spec.share_denominator);
  c.reason = name + " has the highest " + score + " in " + count_text(wins, total) + " rows (needs " + share + ")";
  return c;
}

// every_row and dataset_order: one comparison per row (scenario), which must hold in all of them.
ClaimResult every_group(const ClaimPlan& p, ClaimResult c) {
  const ClaimSpec& spec = *p.spec;
  const bool order = spec.kind == ClaimKind::kDatasetOrder;
  const std::string name = algo_display_name(spec.algo);
  if (order) c.header = {"scenario", name + " " + spec.below, name + " " + spec.above_dataset, "holds"};
  else
    c.header = {"scenario / dataset", name + " " + score_name(spec.metric),
                algo_display_name(spec.other) + " " + score_name(spec.metric), "holds"};
  int holds = 0;
  for (const PlannedGroup& g : p.groups) {
    const PlannedComparison& cmp = g.comparisons.front();
    // The table shows the lower side first for dataset_order (its y), x first otherwise.
    const std::optional<double> a = point(cmp.measure, order ? cmp.y_cell : cmp.x_cell),
                               b = point(cmp.measure, order ? cmp.x_cell : cmp.y_cell);
    const bool below = order || cmp.wanted == ComparisonOutcome::kYBetter;
    const bool ok = a && b && (below ? *a < *b : *a > *b);
    holds += ok;
    c.rows.push_back({g.label, short_number(a), short_number(b), yes_no(ok, a && b)});
  }
  const int total = static_cast<int>(p.groups.size());
  c.verdict = holds == total && total > 0 ? "PASS" : "FAIL";
  c.reason = "holds in " + count_text(holds, total) + (order ? " scenarios" : " rows") + " (needs all)";
  return c;
}

// Mean prior and online BC loss over the steps both curves have within [from, to], and the
// fraction of those steps where prior < online.
struct BcWindow {
  int points = 0;
  double prior = 0.0, online = 0.0, below_fraction = 0.0;
};

BcWindow bc_window(const CellSummary& cell, double from, double to) {
  BcWindow w;
  for (std::size_t i = 0; i < cell.bc_prior.step.size(); ++i) {
    const double step = cell.bc_prior.step[i];
    if (step < from || step > to) continue;
    const auto it = std::find(cell.bc_online.step.begin(), cell.bc_online.step.end(), step);
    if (it == cell.bc_online.step.end()) continue;
    const double online = cell.bc_online.mean[static_cast<std::size_t>(it - cell.bc_online.step.begin())];
    w.points += 1;
    w.prior += cell.bc_prior.mean[i];
    w.online += online;
    w.below_fraction += cell.bc_prior.mean[i] < online;
  }
  if (w.points > 0) {
    w.prior /= w.points;
    w.online /= w.points;
    w.below_fraction /= w.points;
  }
  return w;
}

std::string count_word(std::size_t n) {
  static const char* kWords[] = {"no", "one", "two", "three", "four", "five", "six", "seven", "eight", "nine", "ten"};
  return n < std::size(kWords) ? kWords[n] : std::to_string(n);
}

// bc_windows: each window's mean prior and online BC loss on the seed-mean curves.
ClaimResult bc_windows(const ClaimPlan& p, ClaimResult c) {
  c.header = {"dataset", "steps", "mean prior BC", "mean online BC", "prior < online at", "expected", "holds"};
  bool all = true;
  std::size_t n = 0;
  for (const PlannedGroup& g : p.groups)
    for (const PlannedComparison& cmp : g.comparisons) {
      const BcWindow w = cmp.x_cell ? bc_window(*cmp.x_cell, cmp.from, cmp.to) : BcWindow{};
      const bool prior_below = cmp.wanted == ComparisonOutcome::kYBetter;
      const bool ok = w.points > 0 && (prior_below ? w.prior < w.online : w.prior > w.online);
      all = all && ok;
      ++n;
      c.rows.push_back({cmp.dataset, cmp.window, w.points ? short_number(w.prior) : "—", w.points ? short_number(w.online) : "—",
                        w.points ? std::to_string(static_cast<int>(std::lround(w.below_fraction * w.points))) + " of " +
                                       std::to_string(w.points) + " steps"
                                 : "no data",
                        prior_below ? "prior < online" : "prior > online", ok ? "yes" : "no"});
    }
  c.verdict = all ? "PASS" : "FAIL";
  c.reason = all ? "all " + count_word(n) + " comparisons hold" : "not every comparison holds (see the table)";
  return c;
}

}  // namespace

std::vector<ClaimResult> check_claims(const Summary& s) {
  std::vector<ClaimResult> out;
  for (const ClaimPlan& p : plan_claims(s)) {
    ClaimResult c = claim(p.spec->id, p.spec->statement, p.spec->definition);
    // The claims are about Table I; with axes each row is one setting among several, and a verdict
    // over all of them would mix settings the paper never compared.
    if (!s.grid.axes.empty())
      c = not_applicable(std::move(c), "the grid has axes: the claims are checked on grids without (see the sensitivity section)");
    else if (!p.not_applicable.empty()) c = not_applicable(std::move(c), p.not_applicable);
    else switch (p.spec->kind) {
        case ClaimKind::kMostRows: c = most_rows_best(p, std::move(c)); break;
        case ClaimKind::kEveryRow:
        case ClaimKind::kDatasetOrder: c = every_group(p, std::move(c)); break;
        case ClaimKind::kBcWindows: c = bc_windows(p, std::move(c)); break;
      }
    out.push_back(std::move(c));
  }
  return out;
}

const ClaimResult* point_mean_claim(const Summary& summary, const std::string& id) {
  for (const ClaimResult& c : summary.claims)
    if (c.id == id) return &c;
  return nullptr;
}

}  // namespace rapid
