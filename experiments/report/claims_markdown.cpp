#include "experiments/report/claims_markdown.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <sstream>

#include "algos/registry.hpp"
#include "core/hypothesis_tests.hpp"
#include "core/printable.hpp"
#include "experiments/report/adaptive_seeds.hpp"
#include "experiments/report/claims.hpp"
#include "experiments/report/decisions.hpp"
#include "experiments/report/format.hpp"

namespace rapid {

namespace {

std::string markdown_table(const ClaimResult& c) {
  if (c.header.empty()) return "";
  std::ostringstream out;
  out << "|";
  for (const auto& h : c.header) out << " " << h << " |";
  out << "\n|";
  for (std::size_t i = 0; i < c.header.size(); ++i) out << "---|";
  out << "\n";
  for (const auto& row : c.rows) {
    out << "|";
    for (const auto& cell : row) out << " " << cell << " |";
    out << "\n";
  }
  return out.str();
}

// The claims are the paper's: an algorithm it does not have is left out of them (C1 and C5 compare
// RAPID-RL with the paper's algorithms only). Empty for a grid of the paper's algorithms.
std::string non_paper_note(const Summary& s) {
  std::string names;
  for (const Algorithm* a : rows_in_table_order(s.grid.algos))
    if (!a->in_paper) names += (names.empty() ? "" : ", ") + a->display_name;
  if (names.empty()) return "";
  return "The grid also has " + names +
         ", which the paper does not have: the claims leave it out (in C1 and C5 RAPID-RL is compared with the "
         "paper's algorithms only).\n\n";
}

// A comparison's outcome in words: which side is higher, or within ±δ.
std::string outcome_text(const Comparison& c, ComparisonOutcome o) {
  switch (o) {
    case ComparisonOutcome::kXBetter: return c.x + " higher";
    case ComparisonOutcome::kYBetter: return c.y + " higher";
    case ComparisonOutcome::kEquivalent: return "within ±" + short_number(c.delta);
    case ComparisonOutcome::kUndecided: return "undecided";
  }
  return "?";
}

std::string p_text(double p) {
  if (std::isnan(p)) return "—";
  char buf[32];
  std::snprintf(buf, sizeof buf, p < 0.001 ? "%.1e" : "%.3f", p);
  return buf;
}

std::string decided_intro(const Decisions& d) {
  std::ostringstream out;
  out << "Verdicts are decided (docs/decisions.md): each claim's comparisons are tested on the per-seed numbers "
         "(Welch's t test for a difference, TOST for equivalence within ±δ), "
      << d.family_size << " hypotheses under Holm's procedure at a family-wise error of α = " << d.settings.alpha;
  if (d.settings.looks > 1)
    out << " over at most " << d.settings.looks << " looks of adaptive seeds (`--decide`): each look decides at α/"
        << d.settings.looks << " = " << d.settings.alpha_per_look() << "; each cell's seeds are in table.md's (n=…)";
  out << ". δ:";
  for (const auto& [scenario, delta] : d.settings.delta) out << " " << scenario << " " << short_number(delta) << ";";
  out << " " << d.settings.delta_rule << ". CONFIRMED: the claim holds even if every undecided comparison went "
      << "against it; REFUTED: it fails even if every undecided comparison went for it; UNDECIDED otherwise. "
      << "\"Seeds to resolve\": per algorithm, for power " << d.settings.power
      << " against a difference of δ at the observed spread. The point-mean verdict (PASS/FAIL on means alone, not a "
         "decision) is kept beside it.\n\n";
  return out.str();
}

// The comparisons `which` of `d`, one line each; `claim_column`: with the outcome a claim needs.
std::string comparisons_table(const Decisions& d, const std::vector<std::size_t>& which, bool claim_column) {
  if (which.empty()) return "";
  std::ostringstream out;
  out << "| where | metric | x vs y | seeds | x − y | p (difference) | p (within ±δ) | outcome | "
      << (claim_column ? "the claim needs | " : "") << "seeds to resolve |\n|---|---|---|---|---:|---:|---:|---|"
      << (claim_column ? "---|" : "") << "---:|\n";
  for (std::size_t i : which) {
    const Comparison& c = d.comparisons[i];
    out << "| " << c.where << " | " << c.metric << " | " << c.x << " vs " << c.y << (c.paired ? " (paired)" : "") << " | "
        << c.xs.size() << " / " << c.ys.size() << " | " << short_number(c.d.diff) << " | " << p_text(c.p_difference)
        << " | " << p_text(c.p_equivalence) << " | " << outcome_text(c, c.outcome)
        << (c.frozen.empty() ? "" : " (" + c.frozen + ")") << " | "
        << (claim_column ? outcome_text(c, c.wanted) + " | " : "")
        << (c.seeds_needed ? std::to_string(*c.seeds_needed) : "—") << " |\n";
  }
  return out.str();
}

// RAPID-RL against the baselines the paper does not run (decide_published_baselines): how many rows
// each comparison's outcome took, then every comparison.
std::string baseline_decisions_markdown(const Summary& s) {
  if (!s.baseline_decisions) return "";
  const Decisions& d = *s.baseline_decisions;
  const std::vector<BaselineTally> tallies = tally_published_baselines(s);
  std::vector<std::string> names;
  for (const BaselineTally& t : tallies) names.push_back(t.name);
  std::ostringstream out;
  out << "\n## Beside the claims: RAPID-RL against " << comma_joined(names)
      << "\n\nBaselines the paper does not run. RAPID-RL's final returns against each in every row, by the claims' tests "
         "(Welch's t test, TOST within ±δ) but as a family of their own: "
      << d.family_size << " hypotheses under Holm's procedure at α = " << short_number(d.settings.alpha_per_look())
      << ", apart from the claims' family, so the claims' verdicts above are those the grid would get without these "
         "baselines. \"Seeds to resolve\" as above.\n\n"
      << "| baseline | rows | RAPID-RL higher | baseline higher | within ±δ | undecided |\n|---|---:|---:|---:|---:|---:|\n";
  for (const BaselineTally& t : tallies)
    out << "| " << t.name << " | " << t.rows << " | " << t.rapid_rl_higher << " | " << t.baseline_higher << " | "
        << t.equivalent << " | " << t.undecided << " |\n";
  std::vector<std::size_t> all(d.comparisons.size());
  std::iota(all.begin(), all.end(), std::size_t{0});
  out << "\n" << comparisons_table(d, all, /*claim_column=*/false);
  return out.str();
}

// The aggregate claims (decide_aggregate_claims): each contrast's estimate, interval, both p-values
// raw and Holm-adjusted, and its outcome. First in claims.md: they are the registered question.
std::string aggregate_decisions_markdown(const Summary& s) {
  if (!s.aggregate_decisions) return "";
  const Decisions& d = *s.aggregate_decisions;
  const std::vector<AggregateClaimSpec> specs = aggregate_claims_of(s);
  std::vector<double> p;
  for (const Comparison& c : d.comparisons) {
    p.push_back(c.p_difference);
    p.push_back(c.p_equivalence);
  }
  const std::vector<double> adjusted = holm_adjusted(p);
  const bool registered = std::any_of(specs.begin(), specs.end(), [](const AggregateClaimSpec& a) { return a.registered; });
  std::ostringstream out;
  out << "\n## The aggregate claims" << (registered ? " (pre-registered: docs/confirmatory.md)" : "") << "\n\n"
      << "Each is one paired comparison: per seed, the mean over the table's rows of the two algorithms' final returns, "
         "each in δ units of its row's scenario. A one-sample t test on the per-seed differences decides a difference "
         "(two-sided), TOST within ±margin decides equivalence, and all "
      << d.family_size << " hypotheses form one Holm family at α = " << short_number(d.settings.alpha)
      << ", apart from the paper's claims. Equivalence wins when both reject. A seed counts only with a value in every "
         "row on both sides. The interval is the unadjusted 95 % t interval.\n\n"
      << "| claim | comparison | seeds | mean difference (δ) | 95 % interval | sd | p difference (Holm) | p equivalence (Holm) "
         "| outcome | seeds to resolve |\n|---|---|---|---:|---|---:|---:|---:|---|---:|\n";
  for (std::size_t i = 0; i < d.comparisons.size(); ++i) {
    const Comparison& c = d.comparisons[i];
    const std::string id = i < specs.size() ? specs[i].id : "";
    const double half = std::isfinite(c.d.se) && c.d.df > 0 ? student_t_quantile(0.975, c.d.df) * c.d.se : NAN;
    const double sd = std::isfinite(c.d.se) ? c.d.se * std::sqrt(static_cast<double>(c.xs.size())) : NAN;
    out << "| " << markdown_text(id) << " | " << c.x << " − " << c.y << " | " << markdown_text(c.where.substr(c.where.find(": ") + 2))
        << " | " << short_number(c.d.diff) << " | "
        << (std::isfinite(half) ? std::string("[").append(short_number(c.d.diff - half)).append(", ").append(short_number(c.d.diff + half)).append("]")
                                : std::string("—"))
        << " | " << short_number(sd) << " | " << p_text(c.p_difference) << " (" << p_text(adjusted[2 * i]) << ") | "
        << p_text(c.p_equivalence) << " (" << p_text(adjusted[2 * i + 1]) << ") | " << outcome_text(c, c.outcome) << " | "
        << (c.seeds_needed ? std::to_string(*c.seeds_needed) : "—") << " |\n";
  }
  out << "\n";
  for (const AggregateClaimSpec& a : specs) out << "- " << markdown_text(a.id) << ": " << markdown_text(a.statement) << "\n";
  return out.str();
}

// claims.md with decided verdicts, the point-mean ones beside them.
std::string decided_claims_markdown(const Summary& s) {
  const Decisions& d = *s.decisions;
  std::ostringstream out;
  out << "# Claims decided — grid `" << s.grid.name << "`\n" << aggregate_decisions_markdown(s) << "\n" << decided_intro(d)
      << non_paper_note(s)
      << "| Claim | Verdict | Why | Point-mean verdict |\n|---|---|---|---|\n";
  for (const DecidedClaim& c : d.claims) {
    const ClaimResult* pm = point_mean_claim(s, c.id);
    out << "| " << markdown_text(c.id) << " | " << c.verdict << " | " << c.reason << " | " << (pm ? pm->verdict : "—") << " |\n";
  }
  for (const DecidedClaim& c : d.claims) {
    const ClaimResult* pm = point_mean_claim(s, c.id);
    out << "\n## " << markdown_text(c.id) << ": " << c.verdict << "\n\n";
    if (pm) out << "Claim: " << markdown_text(pm->statement) << "\n\n";
    out << "Decided: " << c.reason << ".\n";
    const std::string table = comparisons_table(d, c.comparisons, /*claim_column=*/true);
    if (!table.empty()) out << "\n" << table;
    if (pm) {
      out << "\nPoint-mean check (not a decision): " << pm->verdict << ". " << markdown_text(pm->definition) << " " << pm->reason << ".\n";
      const std::string means = markdown_table(*pm);
      if (!means.empty()) out << "\n" << means;
    }
  }
  out << baseline_decisions_markdown(s) << adaptive_seeds_markdown(s.adaptive_seeds);
  return out.str();
}

}  // namespace

std::string claims_markdown(const Summary& s) {
  if (s.decisions) return decided_claims_markdown(s);
  std::ostringstream out;
  out << "# Claims check — grid `" << s.grid.name << "`\n\n"
      << "Each claim of the paper (docs/reports.md §claims.md) checked against this sweep's ok runs. Values are means over seeds of the "
         "final return (or of a curve). PASS/FAIL is decided by the definition printed under each claim; N/A means the "
         "grid does not contain what the claim is about. A row whose cells have no ok seed counts against the claim. "
         "With few seeds a verdict is weak evidence: look at the intervals in summary.json and table.md.\n\n"
      << non_paper_note(s) << "| Claim | Verdict | Why |\n|---|---|---|\n";
  for (const ClaimResult& c : s.claims) out << "| " << markdown_text(c.id) << " | " << c.verdict << " | " << c.reason << " |\n";
  for (const ClaimResult& c : s.claims) {
    out << "\n## " << markdown_text(c.id) << ": " << c.verdict << "\n\n"
        << "Claim: " << markdown_text(c.statement) << "\n\n"
        << "Checked: " << markdown_text(c.definition) << "\n\n"
        << "Result: " << c.reason << ".\n";
    const std::string table = markdown_table(c);
    if (!table.empty()) out << "\n" << table;
  }
  return out.str();
}

}  // namespace rapid
