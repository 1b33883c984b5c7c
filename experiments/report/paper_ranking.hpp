// The paper beside us (docs/reports.md): the paper's Table I means are published facts, but its
// reward scale is not ours (its SUMO set-up and reward constants are not published in full), so
// what can honestly be compared is the order of the methods within each row. Per row of our
// Table I that the paper also has, Kendall's τ-b between the paper's means and ours over the
// methods both have, a bootstrap interval over our seeds, whether the best method agrees, and a
// permutation test of the mean τ against method labels that carry no information.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/statistics.hpp"

namespace rapid {

// One value of the paper's Table I: mean ± std over its 10 seeds.
struct PublishedCell {
  std::string scenario, dataset, algo;
  double mean = 0.0, std = 0.0;
};

// Every value of Table I that the paper's text gives (../shared/paper.txt). The RAPID-RL column
// of cut-in and merge is not in it, so those rows rank four methods.
const std::vector<PublishedCell>& paper_table_i();

// A row of our Table I: each algorithm's ok final returns (dataset "none" cells, DDPG's, appear in
// every dataset row as in the table).
struct OurRow {
  std::string scenario, dataset;
  std::vector<std::pair<std::string, std::vector<double>>> finals;  // (algo, ok seeds' finals)
};

// Our rows as summary.json's "table" and "cells" give them; rows with axis values are left out
// (the paper has no axes).
std::vector<OurRow> our_rows(const nlohmann::json& summary);

struct RankedMethod {
  std::string algo;
  double mean = 0.0;
};

struct RowAgreement {
  std::string scenario, dataset;
  std::vector<RankedMethod> paper, ours;  // the methods both have, best first
  // The same methods in name order, with the paper's means and ours in that order: what the
  // permutation test relabels.
  std::vector<std::string> names;
  std::vector<double> paper_by_name, ours_by_name;
  double tau = 0.0;                       // Kendall's τ-b of the two orders
  std::optional<Interval> tau_ci;         // 95% stratified bootstrap over our seeds
  bool same_best = false;
};

struct PaperAgreement {
  std::vector<RowAgreement> rows;  // in our table's order
  double mean_tau = 0.0;
  // P(mean τ ≥ observed) if our method labels carried no information: each scenario's methods
  // relabelled by one random permutation for all its rows (Monte Carlo, kPermutations draws,
  // one-sided: agreement).
  double p_value = 1.0;
  int same_best = 0;
};

inline constexpr int kPermutations = 20000;
// Fewer methods than this in a row and its τ says nothing: the row is left out.
inline constexpr std::size_t kMinRankedMethods = 3;

// Kendall's τ-b of two equally long lists (ties in either count as in scipy.stats.kendalltau);
// NaN when either list has no two distinct values.
double kendall_tau_b(const std::vector<double>& x, const std::vector<double>& y);

// The agreement of our rows with the paper's; nullopt when no row of ours is one of the paper's
// with at least kMinRankedMethods methods on both sides.
std::optional<PaperAgreement> paper_agreement(const std::vector<OurRow>& rows);

// A row's cells as text, unescaped (the page escapes them): the paper's order and ours, best
// first ("RLPD 12.3 > DDPG 10.1 > …"), and the τ interval ("[lo, hi]", "—" without one).
struct RowTexts {
  std::string paper_order, our_order, tau_interval;
};
RowTexts row_texts(const RowAgreement& row);

// table.md's section "The paper beside us" (empty when paper_agreement has nothing), and the
// sentences the page shares with it.
std::string paper_agreement_markdown(const nlohmann::json& summary);
std::string paper_agreement_preamble();
std::string paper_agreement_conclusion(const PaperAgreement& agreement);

}  // namespace rapid
