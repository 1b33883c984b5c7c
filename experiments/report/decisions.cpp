#include "experiments/report/decisions.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <set>
#include <stdexcept>
#include <tuple>

#include "algos/registry.hpp"
#include "core/contains.hpp"
#include "experiments/report/claim_plan.hpp"
#include "experiments/report/curves.hpp"
#include "experiments/report/format.hpp"
#include "core/json_input.hpp"
#include "experiments/run/run_config.hpp"

namespace rapid {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// A claim's groups as indices into the family's comparisons.
struct IndexedClaim {
  std::string id, not_applicable;
  std::vector<std::vector<std::size_t>> groups;
  int needed = 0;
};

std::vector<double> seed_areas(const CellSummary& cell) {
  std::vector<double> out;
  for (const SeedResult& r : cell.seeds) {
    if (!r.final_return || r.eval.empty()) continue;
    MeanCurve curve;
    for (const auto& [step, ret] : r.eval) {
      curve.step.push_back(step);
      curve.mean.push_back(ret);
    }
    if (const auto a = normalized_area(curve)) out.push_back(*a);
  }
  return out;
}

// Per ok seed, the mean prior and online BC loss over the logged steps in [from, to].
std::pair<std::vector<double>, std::vector<double>> seed_bc_means(const CellSummary& cell, double from, double to) {
  std::vector<double> prior, online;
  for (const SeedResult& r : cell.seeds) {
    if (!r.final_return) continue;
    double p = 0.0, o = 0.0;
    int n = 0;
    for (const auto& [step, bp, bo] : r.bc_loss)
      if (step >= from && step <= to && std::isfinite(bp) && std::isfinite(bo)) {
        p += bp;
        o += bo;
        ++n;
      }
    if (n == 0) continue;
    prior.push_back(p / n);
    online.push_back(o / n);
  }
  return {prior, online};
}

class Builder {
 public:
  Builder(const Summary& s, const DecisionSettings& settings, const FrozenComparisons& frozen)
      : s_(s), settings_(settings), frozen_(frozen) {}

  std::size_t add(Comparison c) {
    c.key.clear();
    const int seen = ++keys_seen_[comparison_key(c)];
    c.key = comparison_key(c) + (seen > 1 ? " #" + std::to_string(seen) : "");
    out_.comparisons.push_back(std::move(c));
    return out_.comparisons.size() - 1;
  }

  std::optional<double> delta(const std::string& scenario) const {
    const auto it = settings_.delta.find(scenario);
    return it == settings_.delta.end() ? std::nullopt : std::optional<double>(it->second);
  }

  // A planned claim's comparisons into the family, with their per-seed values.
  IndexedClaim add_plan(const ClaimPlan& p, const std::string& not_applicable) {
    IndexedClaim c{p.spec->id, not_applicable.empty() ? p.not_applicable : not_applicable, {}, p.needed};
    if (!c.not_applicable.empty()) return c;
    for (const PlannedGroup& g : p.groups) {
      std::vector<std::size_t> indices;
      for (const PlannedComparison& planned : g.comparisons) indices.push_back(add(from_plan(planned)));
      c.groups.push_back(std::move(indices));
    }
    return c;
  }

  // Per row, RAPID-RL against each baseline the paper does not run, on final return. Not a claim:
  // each comparison's outcome is the answer.
  void published_baselines(const std::vector<std::string>& baselines) {
    for (const TableRow& row : s_.rows)
      for (const std::string& algo : baselines)
        add(two_sample(row_label(row), "final return", algo_display_name(kRapidRl), algo_display_name(algo),
                       s_.column_cell(row, kRapidRl), s_.column_cell(row, algo), finals, delta(row.scenario)));
  }

  // An aggregate claim (sweep/aggregate_claim.hpp): per seed, the mean over the table's rows of
  // x's and of y's final return in δ units of the row's scenario, paired by seed. A seed counts only
  // with a value in every row on both sides; `where` says how many counted and how many were left out.
  void aggregate(const AggregateClaimSpec& spec) {
    Comparison c;
    c.metric = "final return, mean over rows in δ units";
    c.x = algo_display_name(spec.x);
    c.y = algo_display_name(spec.y);
    c.paired = true;
    c.delta = spec.margin;
    std::map<std::uint64_t, std::pair<double, double>> sums;  // seed → (x, y) summed over rows
    std::map<std::uint64_t, std::size_t> rows_of;             // seed → rows with both values
    std::set<std::uint64_t> seen;                             // every seed the claim uses that a cell has
    bool every_row = !s_.rows.empty();
    for (const TableRow& row : s_.rows) {
      const CellSummary* cx = s_.column_cell(row, spec.x);
      const CellSummary* cy = s_.column_cell(row, spec.y);
      const std::optional<double> d = delta(row.scenario);
      if (!cx || !cy || !d) {
        every_row = false;
        continue;
      }
      for (const CellSummary* cell : {cx, cy})
        if (!contains(c.cells, cell->key())) c.cells.push_back(cell->key());
      std::map<std::uint64_t, double> ys;
      for (const SeedResult& r : cy->seeds)
        if (spec.uses_seed(r.seed)) {
          seen.insert(r.seed);
          if (r.final_return) ys[r.seed] = *r.final_return;
        }
      for (const SeedResult& r : cx->seeds) {
        if (!spec.uses_seed(r.seed)) continue;
        seen.insert(r.seed);
        const auto y = ys.find(r.seed);
        if (!r.final_return || y == ys.end()) continue;
        sums[r.seed].first += *r.final_return / *d;
        sums[r.seed].second += y->second / *d;
        ++rows_of[r.seed];
      }
    }
    if (every_row)
      for (const auto& [seed, sum] : sums)
        if (rows_of[seed] == s_.rows.size()) {
          c.xs.push_back(sum.first / static_cast<double>(s_.rows.size()));
          c.ys.push_back(sum.second / static_cast<double>(s_.rows.size()));
        }
    c.where = spec.id + ": " + std::to_string(s_.rows.size()) + " rows, " + spec.seeds_text() + " (" +
              std::to_string(c.xs.size()) + " complete, " + std::to_string(seen.size() - c.xs.size()) + " left out)";
    add(std::move(c));
  }

  Decisions finish(const std::vector<IndexedClaim>& claims) {
    out_.settings = settings_;
    run_tests();
    for (const IndexedClaim& c : claims)
      out_.claims.push_back(decided_verdict(c.id, c.not_applicable, c.groups, c.needed, out_.comparisons));
    return std::move(out_);
  }

 private:
  static std::vector<double> finals(const CellSummary& c) { return c.finals; }
  static std::string row_label(const TableRow& row) { return row.scenario + " / " + row.dataset; }

  Comparison from_plan(const PlannedComparison& p) const {
    Comparison c;
    c.where = p.where;
    c.metric = p.metric;
    c.x = p.x;
    c.y = p.y;
    c.wanted = p.wanted;
    if (p.bc_loss) {
      c.paired = true;
      if (p.x_cell) {
        std::tie(c.xs, c.ys) = seed_bc_means(*p.x_cell, p.from, p.to);
        c.cells.push_back(p.x_cell->key());
      }
      return c;
    }
    c.delta = delta(p.delta_scenario);
    const auto values = [&](const CellSummary& cell) {
      return p.measure == ClaimMetric::kFinalReturn ? cell.finals : seed_areas(cell);
    };
    for (const CellSummary* cell : {p.x_cell, p.y_cell})
      if (cell) c.cells.push_back(cell->key());
    if (p.x_cell) c.xs = values(*p.x_cell);
    if (p.y_cell) c.ys = values(*p.y_cell);
    return c;
  }

  static Comparison two_sample(std::string where, std::string metric, std::string x, std::string y, const CellSummary* cx,
                               const CellSummary* cy,
                               const std::function<std::vector<double>(const CellSummary&)>& values,
                               std::optional<double> delta) {
    Comparison c;
    c.where = std::move(where);
    c.metric = std::move(metric);
    c.x = std::move(x);
    c.y = std::move(y);
    c.delta = delta;
    for (const CellSummary* cell : {cx, cy})
      if (cell) c.cells.push_back(cell->key());
    if (cx) c.xs = values(*cx);
    if (cy) c.ys = values(*cy);
    return c;
  }

  // Every hypothesis into one Holm family; then each comparison's outcome and, if undecided, the
  // seeds that would resolve it.
  // A comparison frozen at an earlier look (docs/decisions.md §Adaptive seeds) keeps its outcome and
  // statistics from then and stays in the family with p = 0 for the hypothesis it rejected and 1
  // for the others, so the family's size does not change from look to look.
  void run_tests() {
    std::vector<double> p;
    std::vector<std::pair<std::size_t, bool>> owner;  // (comparison, is the equivalence test)
    for (std::size_t i = 0; i < out_.comparisons.size(); ++i) {
      Comparison& c = out_.comparisons[i];
      const auto was = frozen_.find(comparison_key(c));
      if (was != frozen_.end()) {
        c = was->second;
        p.push_back(c.outcome == ComparisonOutcome::kXBetter || c.outcome == ComparisonOutcome::kYBetter ? 0.0 : 1.0);
      } else {
        c.d = c.paired && c.xs.size() == c.ys.size() ? paired_difference(c.xs, c.ys) : welch_difference(c.xs, c.ys);
        c.p_difference = p_difference(c.d);
        c.p_equivalence = c.delta ? p_equivalence(c.d, *c.delta) : kNaN;
        p.push_back(c.p_difference);
      }
      owner.emplace_back(i, false);
      if (c.delta) {
        p.push_back(was == frozen_.end() ? c.p_equivalence : c.outcome == ComparisonOutcome::kEquivalent ? 0.0 : 1.0);
        owner.emplace_back(i, true);
      }
    }
    out_.family_size = static_cast<int>(p.size());
    const std::vector<bool> rejected = holm_rejections(p, settings_.alpha_per_look());
    for (std::size_t k = 0; k < p.size(); ++k) {
      if (!rejected[k]) continue;
      Comparison& c = out_.comparisons[owner[k].first];
      if (!c.frozen.empty()) continue;
      // A difference shown to lie within ±δ is no win (docs/decisions.md): when both tests reject,
      // the comparison is equivalent. A comparison's equivalence test follows its difference test.
      if (owner[k].second) c.outcome = ComparisonOutcome::kEquivalent;
      else c.outcome = c.d.diff > 0 ? ComparisonOutcome::kXBetter : ComparisonOutcome::kYBetter;
    }
    for (Comparison& c : out_.comparisons) {
      if (c.outcome != ComparisonOutcome::kUndecided || std::isnan(c.d.se) || !c.frozen.empty()) continue;
      const double effect = c.delta ? *c.delta : std::abs(c.d.diff);
      if (!(effect > 0.0)) continue;
      // The spread behind the standard error, per side (paired: of the differences, over √2).
      const double sd = c.paired ? c.d.se * std::sqrt(static_cast<double>(c.xs.size())) / std::sqrt(2.0)
                                 : c.d.se / std::sqrt(1.0 / c.xs.size() + 1.0 / c.ys.size());
      c.seeds_needed =
          seeds_needed(sd, effect, settings_.alpha_per_look() / std::max(1, out_.family_size), settings_.power);
    }
  }

  const Summary& s_;
  const DecisionSettings& settings_;
  const FrozenComparisons& frozen_;
  std::map<std::string, int> keys_seen_;
  Decisions out_;
};

}  // namespace

const char* outcome_name(ComparisonOutcome o) {
  switch (o) {
    case ComparisonOutcome::kXBetter: return "x better";
    case ComparisonOutcome::kYBetter: return "y better";
    case ComparisonOutcome::kEquivalent: return "equivalent";
    case ComparisonOutcome::kUndecided: return "undecided";
  }
  return "?";
}

std::optional<DecisionSettings> load_decision_settings(const std::string& profile) {
  const std::string path = config_dir() + "/" + profile + "/decisions.json";
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return std::nullopt;
  const auto fail = [&](const std::string& why) { throw std::invalid_argument("decision settings " + path + ": " + why); };
  nlohmann::json j;
  try {
    j = read_json_input(path);
  } catch (const std::invalid_argument& e) {
    fail(e.what());
  }
  DecisionSettings s;
  const auto in_unit = [&](const char* key, double& field) {
    if (!j.contains(key) || !j[key].is_number() || !(j[key].get<double>() > 0.0 && j[key].get<double>() < 1.0))
      fail(std::string(key) + ": expected a number in (0, 1)");
    field = j[key].get<double>();
  };
  in_unit("alpha", s.alpha);
  in_unit("power", s.power);
  if (!j.contains("delta") || !j["delta"].is_object()) fail("delta: expected an object of scenario: margin");
  for (const auto& [scenario, v] : j["delta"].items()) {
    if (!v.is_number() || !(v.get<double>() > 0.0)) fail("delta." + scenario + ": expected a positive number");
    s.delta[scenario] = v.get<double>();
  }
  s.delta_rule = j.value("delta_rule", "");
  return s;
}

Decisions decide_claims(const Summary& s, const DecisionSettings& settings, const FrozenComparisons& frozen) {
  Builder b(s, settings, frozen);
  const std::string axes = s.grid.axes.empty() ? "" : "the grid has axes: the claims are checked on grids without";
  std::vector<IndexedClaim> claims;
  for (const ClaimPlan& p : plan_claims(s)) claims.push_back(b.add_plan(p, axes));
  return b.finish(claims);
}

DecidedClaim decided_verdict(const std::string& id, const std::string& not_applicable,
                             const std::vector<std::vector<std::size_t>>& groups, int needed,
                             const std::vector<Comparison>& comparisons) {
  DecidedClaim d;
  d.id = id;
  if (!not_applicable.empty()) {
    d.verdict = "N/A";
    d.reason = not_applicable;
    return d;
  }
  int sure = 0, possible = 0, undecided = 0;
  for (const std::vector<std::size_t>& g : groups) {
    bool all_for = true, none_against = true;
    for (std::size_t i : g) {
      const Comparison& c = comparisons.at(i);
      d.comparisons.push_back(i);
      all_for = all_for && c.outcome == c.wanted;
      none_against = none_against && (c.outcome == c.wanted || c.outcome == ComparisonOutcome::kUndecided);
      undecided += c.outcome == ComparisonOutcome::kUndecided;
    }
    sure += all_for;
    possible += none_against;
  }
  const int total = static_cast<int>(groups.size());
  if (total > 0 && sure >= needed) d.verdict = "CONFIRMED";
  else if (total == 0 || possible < needed) d.verdict = "REFUTED";
  else d.verdict = "UNDECIDED";
  d.reason = std::to_string(sure) + " of " + std::to_string(total) + " hold as decided, " + std::to_string(possible) +
             " could (needs " + std::to_string(needed) + "); " + std::to_string(undecided) + " comparison" +
             (undecided == 1 ? "" : "s") + " undecided";
  return d;
}

std::vector<std::string> published_baselines(const Summary& s) {
  std::vector<std::string> out;
  for (const std::string& algo : s.grid.algos)
    if (is_baseline(algo) && !find_algorithm(algo).in_paper) out.push_back(algo);
  return out;
}

std::optional<Decisions> decide_published_baselines(const Summary& s, const DecisionSettings& settings) {
  const std::vector<std::string> baselines = published_baselines(s);
  if (baselines.empty() || !contains(s.grid.algos, kRapidRl) || !s.grid.axes.empty()) return std::nullopt;
  const FrozenComparisons none;
  Builder b(s, settings, none);
  b.published_baselines(baselines);
  return b.finish({});
}

std::vector<AggregateClaimSpec> aggregate_claims_of(const Summary& s) {
  std::vector<AggregateClaimSpec> specs = registered_aggregate_claims(s.grid.name);
  specs.insert(specs.end(), s.grid.aggregate_claims.begin(), s.grid.aggregate_claims.end());
  return specs;
}

std::optional<Decisions> decide_aggregate_claims(const Summary& s, const DecisionSettings& settings) {
  const std::vector<AggregateClaimSpec> specs = aggregate_claims_of(s);
  if (specs.empty() || !s.grid.axes.empty()) return std::nullopt;
  const FrozenComparisons none;
  DecisionSettings once = settings;
  once.looks = 1;  // fixed seeds, one analysis: the looks of --decide chase the paper's claims only
  Builder b(s, once, none);
  for (const AggregateClaimSpec& spec : specs) b.aggregate(spec);
  return b.finish({});
}

std::vector<BaselineTally> tally_published_baselines(const Summary& s) {
  std::vector<BaselineTally> out;
  if (!s.baseline_decisions) return out;
  for (const std::string& algo : published_baselines(s)) {
    BaselineTally t;
    t.name = algo_display_name(algo);
    for (const Comparison& c : s.baseline_decisions->comparisons) {
      if (c.y != t.name) continue;
      ++t.rows;
      switch (c.outcome) {
        case ComparisonOutcome::kXBetter: ++t.rapid_rl_higher; break;
        case ComparisonOutcome::kYBetter: ++t.baseline_higher; break;
        case ComparisonOutcome::kEquivalent: ++t.equivalent; break;
        case ComparisonOutcome::kUndecided: ++t.undecided; break;
      }
    }
    out.push_back(t);
  }
  return out;
}

}  // namespace rapid
