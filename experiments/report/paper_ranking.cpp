#include "experiments/report/paper_ranking.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <sstream>

#include "experiments/report/format.hpp"
#include "experiments/report/summary.hpp"
#include "experiments/run/json_numbers.hpp"

namespace rapid {

const std::vector<PublishedCell>& paper_table_i() {
  // Table I of the paper, as its text gives it (mean ± std over 10 seeds). DDPG uses no dataset:
  // one value per scenario, in every row. Merge's DDPG value repeats CoL-prior's Initial value
  // digit for digit in the paper; it is kept as published.
  static const std::vector<PublishedCell> table = [] {
    std::vector<PublishedCell> t;
    const auto add = [&](const char* scenario, const char* algo, std::vector<std::pair<double, double>> per_dataset) {
      static const char* kDatasets[] = {"initial", "medium", "final+medium"};
      for (std::size_t i = 0; i < per_dataset.size(); ++i)
        t.push_back({scenario, kDatasets[i], algo, per_dataset[i].first, per_dataset[i].second});
    };
    const auto ddpg = [&](const char* scenario, double mean, double std) {
      add(scenario, "ddpg", {{mean, std}, {mean, std}, {mean, std}});
    };
    add("lane-drop", "rapid-rl", {{939.7, 52.4}, {946.5, 110.2}, {915.6, 88.2}});
    add("lane-drop", "rlpd", {{765.4, 190.2}, {739.0, 174.0}, {634.6, 200.7}});
    add("lane-drop", "col-prior", {{485.8, 213.2}, {611.2, 112.0}, {690.6, 167.9}});
    add("lane-drop", "col-all", {{14.3, 3.2}, {11.2, 3.3}, {3.2, 7.1}});
    ddpg("lane-drop", 566.3, 165.8);
    add("cut-in", "rlpd", {{1109.2, 52.2}, {1157.6, 155.1}, {1155.8, 137.9}});
    add("cut-in", "col-prior", {{1071.5, 64.1}, {1127.7, 66.7}, {1288.3, 160.9}});
    add("cut-in", "col-all", {{113.7, 336.7}, {104.0, 322.5}, {327.5, 445.9}});
    ddpg("cut-in", 1064.0, 314.6);
    add("merge", "rlpd", {{1716.0, 237.6}, {1709.5, 99.7}, {1588.5, 289.4}});
    add("merge", "col-prior", {{1618.4, 171.8}, {2131.15, 158.1}, {2186.9, 290.8}});
    add("merge", "col-all", {{962.0, 529.7}, {1170.3, 900.0}, {1128.8, 851.4}});
    ddpg("merge", 1618.4, 171.8);
    return t;
  }();
  return table;
}

std::vector<OurRow> our_rows(const nlohmann::json& summary) {
  std::map<std::string, std::vector<double>> finals_of;  // cell key → ok finals
  for (const nlohmann::json& cell : summary.value("cells", nlohmann::json::array())) {
    if (cell.contains("axis") && !cell["axis"].empty()) continue;
    std::vector<double>& finals = finals_of[summary_cell_key(cell)];
    for (const nlohmann::json& seed : cell.value("seeds", nlohmann::json::array()))
      if (const std::optional<double> f = optional_number(seed, "final"); f && seed.value("status", "") == "ok")
        finals.push_back(*f);
  }
  std::vector<OurRow> rows;
  for (const nlohmann::json& row : summary.value("table", nlohmann::json::array())) {
    if (row.contains("axis") || !row.value("dataset", nlohmann::json()).is_string()) continue;
    OurRow r{row.value("scenario", ""), row["dataset"].get<std::string>(), {}};
    for (const nlohmann::json& column : row.value("columns", nlohmann::json::array()))
      if (const auto it = finals_of.find(column.value("cell", "")); it != finals_of.end())
        r.finals.emplace_back(column.value("algo", ""), it->second);
    rows.push_back(std::move(r));
  }
  return rows;
}

double kendall_tau_b(const std::vector<double>& x, const std::vector<double>& y) {
  double concordant = 0, discordant = 0, tied_x = 0, tied_y = 0, pairs = 0;
  for (std::size_t i = 0; i < x.size(); ++i)
    for (std::size_t j = i + 1; j < x.size(); ++j) {
      const double dx = x[i] - x[j], dy = y[i] - y[j];
      pairs += 1;
      if (dx == 0) tied_x += 1;
      if (dy == 0) tied_y += 1;
      if (dx * dy > 0) concordant += 1;
      if (dx * dy < 0) discordant += 1;
    }
  const double denominator = std::sqrt((pairs - tied_x) * (pairs - tied_y));
  return denominator > 0 ? (concordant - discordant) / denominator : std::nan("");
}

namespace {

std::vector<RankedMethod> best_first(std::vector<RankedMethod> methods) {
  std::stable_sort(methods.begin(), methods.end(), [](const RankedMethod& a, const RankedMethod& b) { return a.mean > b.mean; });
  return methods;
}

// One row's agreement, or nullopt when fewer than kMinRankedMethods methods have a value on both
// sides. `row_index` seeds its bootstrap, so every row draws its own replicates.
std::optional<RowAgreement> row_agreement(const OurRow& row, std::size_t row_index, std::vector<double>& paper_means,
                                          Strata& our_finals) {
  RowAgreement out{row.scenario, row.dataset, {}, {}, {}, {}, {}, 0.0, std::nullopt, false};
  paper_means.clear();
  our_finals.clear();
  for (const auto& [algo, finals] : row.finals) {
    const auto published = std::find_if(paper_table_i().begin(), paper_table_i().end(), [&](const PublishedCell& c) {
      return c.scenario == row.scenario && c.dataset == row.dataset && c.algo == algo;
    });
    if (published == paper_table_i().end() || finals.empty()) continue;
    paper_means.push_back(published->mean);
    our_finals.push_back(finals);
    out.paper.push_back({algo, published->mean});
    out.ours.push_back({algo, mean(finals)});
  }
  if (out.paper.size() < kMinRankedMethods) return std::nullopt;
  std::vector<double> our_means;
  for (const RankedMethod& m : out.ours) our_means.push_back(m.mean);
  out.tau = kendall_tau_b(paper_means, our_means);
  const std::vector<double> paper = paper_means;
  const auto tau_of = [paper](const Strata& strata) {
    std::vector<double> means;
    for (const std::vector<double>& s : strata) means.push_back(mean(s));
    return kendall_tau_b(paper, means);
  };
  out.tau_ci = stratified_bootstrap_ci(our_finals, tau_of, BootstrapOptions{2000, 0x7a5u + row_index, 0.95});
  for (const RankedMethod& m : out.paper) out.names.push_back(m.algo);
  std::sort(out.names.begin(), out.names.end());
  const auto mean_of = [](const std::vector<RankedMethod>& methods, const std::string& algo) {
    return std::find_if(methods.begin(), methods.end(), [&](const RankedMethod& m) { return m.algo == algo; })->mean;
  };
  for (const std::string& name : out.names) {
    out.paper_by_name.push_back(mean_of(out.paper, name));
    out.ours_by_name.push_back(mean_of(out.ours, name));
  }
  out.paper = best_first(out.paper);
  out.ours = best_first(out.ours);
  out.same_best = out.paper.front().algo == out.ours.front().algo;
  return out;
}

// P(mean τ ≥ observed) when our method labels carry no information: each scenario's methods are
// relabelled by one uniformly random permutation, the same for all its rows, so the rows of a
// scenario (which share DDPG's cell, and much else) stay as dependent as they are. Fisher–Yates
// with the generator's raw output, so the draws are the same on every standard library.
double permutation_p_value(const std::vector<RowAgreement>& rows, double observed) {
  // Rows of a scenario with the same methods form a group and share a permutation.
  std::vector<std::vector<double>> shuffled(rows.size());
  std::vector<std::size_t> group(rows.size());
  std::vector<std::pair<std::string, std::vector<std::string>>> groups;  // (scenario, method names)
  for (std::size_t r = 0; r < rows.size(); ++r) {
    shuffled[r].resize(rows[r].names.size());
    const std::pair<std::string, std::vector<std::string>> key{rows[r].scenario, rows[r].names};
    group[r] = static_cast<std::size_t>(std::find(groups.begin(), groups.end(), key) - groups.begin());
    if (group[r] == groups.size()) groups.push_back(key);
  }
  std::mt19937_64 rng(0x9e3779b97f4a7c15ull);
  std::vector<std::vector<std::size_t>> permutation(groups.size());
  int at_least = 0;
  for (int draw = 0; draw < kPermutations; ++draw) {
    for (std::size_t g = 0; g < permutation.size(); ++g) {
      std::vector<std::size_t>& p = permutation[g];
      p.resize(groups[g].second.size());
      for (std::size_t i = 0; i < p.size(); ++i) p[i] = i;
      for (std::size_t i = p.size() - 1; i > 0; --i) std::swap(p[i], p[rng() % (i + 1)]);
    }
    double total = 0;
    for (std::size_t r = 0; r < rows.size(); ++r) {
      const std::vector<double>& ours = rows[r].ours_by_name;
      for (std::size_t i = 0; i < ours.size(); ++i) shuffled[r][i] = ours[permutation[group[r]][i]];
      total += kendall_tau_b(rows[r].paper_by_name, shuffled[r]);
    }
    if (total / static_cast<double>(rows.size()) >= observed - 1e-12) ++at_least;
  }
  return (1.0 + at_least) / (1.0 + kPermutations);
}

std::string order_text(const std::vector<RankedMethod>& methods) {
  std::string out;
  for (const RankedMethod& m : methods) out += (out.empty() ? "" : " > ") + algo_display_name(m.algo) + " " + fixed(m.mean, 1);
  return out;
}

}  // namespace

RowTexts row_texts(const RowAgreement& row) {
  return {order_text(row.paper), order_text(row.ours),
          row.tau_ci ? "[" + fixed(row.tau_ci->lo, 2) + ", " + fixed(row.tau_ci->hi, 2) + "]" : "—"};
}

std::optional<PaperAgreement> paper_agreement(const std::vector<OurRow>& rows) {
  PaperAgreement out;
  std::vector<double> paper_means;
  Strata our_finals;
  for (const OurRow& row : rows)
    if (auto a = row_agreement(row, out.rows.size(), paper_means, our_finals); a && std::isfinite(a->tau))
      out.rows.push_back(std::move(*a));
  if (out.rows.empty()) return std::nullopt;
  for (const RowAgreement& r : out.rows) {
    out.mean_tau += r.tau / static_cast<double>(out.rows.size());
    out.same_best += r.same_best ? 1 : 0;
  }
  out.p_value = permutation_p_value(out.rows, out.mean_tau);
  return out;
}

std::string paper_agreement_preamble() {
  return "The paper's Table I is a published fact, but its reward scale is not ours (the scenarios here are rebuilt "
         "from the paper's description, not from its files), so the raw numbers are not comparable. What is: the "
         "order of the methods within a row. Per row, Kendall's τ-b between the paper's means and ours over the "
         "methods both have (1: the same order, −1: reversed, 0: unrelated), with a 95% stratified-bootstrap "
         "interval over our seeds. The paper's text gives no RAPID-RL value for cut-in and merge, so those rows rank "
         "four methods. One row's τ is coarse: a random order of five methods has |τ| ≤ 0.6 in 92% of cases, of four "
         "in 67%; read the rows together.";
}

std::string paper_agreement_conclusion(const PaperAgreement& a) {
  std::ostringstream out;
  out << "Over " << a.rows.size() << (a.rows.size() == 1 ? " row" : " rows") << ": mean τ " << fixed(a.mean_tau, 2)
      << "; if our method labels carried no information (each scenario's methods relabelled at random, one "
         "relabelling for all its rows), a mean τ this high or higher would have probability "
      << short_number(a.p_value) << " (permutation test, " << kPermutations
      << " draws). The best method of the row agrees in " << a.same_best << " of " << a.rows.size() << ".";
  return out.str();
}

std::string paper_agreement_markdown(const nlohmann::json& summary) {
  const std::optional<PaperAgreement> agreement = paper_agreement(our_rows(summary));
  if (!agreement) return "";
  std::ostringstream out;
  out << "\n## The paper beside us\n\n" << paper_agreement_preamble() << "\n\n"
      << "| Scenario | Dataset | The paper's order | Our order | τ | 95% interval | Same best |\n"
      << "|---|---|---|---|---:|---:|---|\n";
  for (const RowAgreement& r : agreement->rows) {
    const RowTexts text = row_texts(r);
    out << "| " << scenario_display_name(r.scenario) << " | " << dataset_display_name(r.dataset) << " | "
        << text.paper_order << " | " << text.our_order << " | " << fixed(r.tau, 2) << " | " << text.tau_interval
        << " | " << (r.same_best ? "yes" : "no") << " |\n";
  }
  out << "\n" << paper_agreement_conclusion(*agreement) << "\n";
  return out.str();
}

}  // namespace rapid
