// report.html's tables: Table I, the probability that RAPID-RL beats each baseline, the IQM per
// algorithm. Each numeric cell carries its exact value in data-sort (what the page sorts by and
// what tests/browser compares with summary.json); the text is formatted as table.md has it.
#include <algorithm>
#include <map>

#include "algos/registry.hpp"
#include "experiments/report/format.hpp"
#include "experiments/report/html_text.hpp"
#include "experiments/report/paper_ranking.hpp"
#include "experiments/report/report_page_sections.hpp"
#include "experiments/report/summary.hpp"
#include "experiments/report/summary_svg.hpp"

namespace rapid::report_page {

namespace {

std::string sort_value(std::optional<double> x) { return " data-sort=\"" + exact_number(x) + "\""; }

std::string header(const std::vector<std::string>& names) {
  std::string html = "<thead><tr>";
  for (const std::string& n : names) html += "<th scope=\"col\">" + n + "</th>";
  return html + "</tr></thead>\n";
}

// The grid's algorithms in the registry's order: Table I's columns.
std::vector<std::string> table_columns(const nlohmann::json& summary) {
  return names_in_table_order(summary["grid"].value("algos", std::vector<std::string>{}));
}

std::string table_i(const ReportFolder& folder) {
  const nlohmann::json& s = folder.summary;
  const int decimals = table_decimals_of(s);
  std::map<std::string, std::size_t> index_of;  // cell key → index in summary.json's cells
  for (std::size_t i = 0; i < s["cells"].size(); ++i) index_of[summary_cell_key(s["cells"][i], folder.sweep.grid.axes)] = i;
  const bool axes = !folder.sweep.grid.axes.empty();
  const std::vector<std::string> algos = table_columns(s);

  std::vector<std::string> names = {"Scenario", "Dataset"};
  if (axes) names.push_back("Axes");
  for (const std::string& a : algos) names.push_back(html_escape(algo_display_name(a)));
  std::string html = "<table class=\"sortable numbers\" id=\"table-i-cells\">" + header(names) + "<tbody>\n";
  std::size_t order = 0;
  for (const nlohmann::json& row : s.value("table", nlohmann::json::array())) {
    html += "<tr data-order=\"" + std::to_string(order++) + "\"><td>" +
            html_escape(scenario_display_name(row.value("scenario", ""))) + "</td><td>" +
            html_escape(dataset_display_name(row.value("dataset", ""))) + "</td>";
    if (axes) html += "<td>" + html_escape(axis_text(row.value("axis", nlohmann::json()))) + "</td>";
    for (const std::string& algo : algos) {
      const auto column = std::find_if(row["columns"].begin(), row["columns"].end(),
                                       [&](const nlohmann::json& c) { return c.value("algo", "") == algo; });
      const auto index = column == row["columns"].end() ? index_of.end() : index_of.find(column->value("cell", ""));
      if (index == index_of.end()) {
        html += "<td data-sort=\"\"></td>";
        continue;
      }
      const nlohmann::json& cell = s["cells"][index->second];
      const std::optional<double> mean = optional_number(cell, "mean");
      const bool best = row.value("best", nlohmann::json()) == algo;
      html += "<td class=\"cell" + std::string(best ? " best" : "") + "\" data-cell=\"" + html_escape(index->first) + "\"" +
              sort_value(mean) + "><a href=\"#" + cell_anchor(index->second) + "\">" +
              html_escape(table_cell_text(mean, optional_number(cell, "std"), cell.value("n_ok", 0), cell.value("n_expected", 0),
                                          decimals, " ± ", "—")) +
              "</a></td>";
    }
    html += "</tr>\n";
  }
  return html + "</tbody></table>\n";
}

// An algorithm's colour in the figures, from summary.json's "algorithms" (grey if it has none).
std::string colour_of(const nlohmann::json& summary, const std::string& algo) {
  for (const nlohmann::json& a : summary.value("algorithms", nlohmann::json::array()))
    if (a.value("name", "") == algo && a.contains("colour") && a["colour"].is_string()) return css_colour(a["colour"]);
  return "#7f7f7f";
}

std::optional<double> bound(const nlohmann::json& ci, std::size_t i) {
  return ci.is_array() && ci.size() == 2 ? optional_number(ci[i]) : std::nullopt;
}

// The probability of improvement of every comparison as points with their intervals (rliable's
// figure), beside the table.
std::string poi_plot(const ReportFolder& folder) {
  std::vector<IntervalRow> rows;
  for (const nlohmann::json& e : folder.summary.value("probability_of_improvement", nlohmann::json::array())) {
    const nlohmann::json ci = e.value("ci", nlohmann::json());
    rows.push_back({scenario_display_name(e.value("scenario", "")) + " / " + dataset_display_name(e.value("dataset", "")) +
                        (e.contains("point") ? " (" + e.value("point", "") + ")" : "") + ": " +
                        algo_display_name(e.value("algo", "")) + " > " + algo_display_name(e.value("baseline", "")),
                    optional_number(e, "p"), bound(ci, 0), bound(ci, 1),
                    colour_of(folder.summary, e.value("baseline", ""))});
  }
  const std::string svg = interval_plot_svg(rows, "poi-plot", "P(X > Y)", 0.5, std::pair{0.0, 1.0});
  return svg.empty() ? "" : "<figure>" + svg + "<figcaption>P(X &gt; Y) per comparison with its 95% interval; right of the "
                                                 "dashed line X tends to be better (coloured by Y).</figcaption></figure>\n";
}

// The IQM of every algorithm with its interval (rliable's aggregate figure).
std::string iqm_plot(const ReportFolder& folder) {
  std::vector<IntervalRow> rows;
  for (const nlohmann::json& e : folder.summary.value("aggregate_iqm", nlohmann::json::array())) {
    const nlohmann::json ci = e.value("ci", nlohmann::json());
    rows.push_back({algo_display_name(e.value("algo", "")), optional_number(e, "iqm"), bound(ci, 0), bound(ci, 1),
                    colour_of(folder.summary, e.value("algo", ""))});
  }
  const std::string svg = interval_plot_svg(rows, "iqm-plot", "IQM of the final return");
  return svg.empty() ? "" : "<figure>" + svg + "<figcaption>IQM over all of an algorithm's ok runs with its 95% "
                                                 "stratified-bootstrap interval.</figcaption></figure>\n";
}

// Per scenario, each algorithm's share of ok runs above each final return (rliable's performance
// profile, per scenario because returns are not normalised across them).
std::string profiles(const ReportFolder& folder) {
  std::string html;
  for (const std::string& scenario : folder.summary["grid"].value("scenarios", std::vector<std::string>{})) {
    std::vector<ProfileSeries> series;
    for (const std::string& algo : table_columns(folder.summary)) {
      ProfileSeries s{algo_display_name(algo), colour_of(folder.summary, algo), {}};
      for (const nlohmann::json& cell : folder.summary.value("cells", nlohmann::json::array())) {
        if (cell.value("scenario", "") != scenario || cell.value("algo", "") != algo) continue;
        for (const nlohmann::json& seed : cell.value("seeds", nlohmann::json::array()))
          if (seed.value("status", "") == "ok")
            if (const std::optional<double> f = optional_number(seed, "final")) s.finals.push_back(*f);
      }
      series.push_back(std::move(s));
    }
    html += performance_profile_svg(series, scenario_display_name(scenario));
  }
  return html.empty() ? "" : "<h3>Performance profiles</h3>\n<p>Per scenario, the share of an algorithm's ok runs (every "
                             "dataset and seed) whose final return is above τ: a line above another is better at every "
                             "level.</p>\n<figure class=\"profiles\">" + html + "</figure>\n";
}

std::string poi_table(const ReportFolder& folder) {
  const nlohmann::json entries = folder.summary.value("probability_of_improvement", nlohmann::json::array());
  if (entries.empty()) return "<p>No row has RAPID-RL and another algorithm, so there is nothing to compare.</p>\n";
  const bool points = std::any_of(entries.begin(), entries.end(), [](const nlohmann::json& e) { return e.contains("point"); });
  std::vector<std::string> names = {"Scenario", "Dataset"};
  if (points) names.push_back("Axes");
  names.insert(names.end(), {"Comparison", "P", "95% interval", "n"});
  std::string html = "<table class=\"sortable numbers\" id=\"poi-table\">" + header(names) + "<tbody>\n";
  std::size_t order = 0;
  for (const nlohmann::json& e : entries) {
    const std::optional<double> p = optional_number(e, "p");
    html += "<tr data-order=\"" + std::to_string(order++) + "\"><td>" +
            html_escape(scenario_display_name(e.value("scenario", ""))) + "</td><td>" +
            html_escape(dataset_display_name(e.value("dataset", ""))) + "</td>";
    if (points) html += "<td>" + html_escape(e.value("point", "")) + "</td>";
    html += "<td>" + html_escape(algo_display_name(e.value("algo", ""))) + " &gt; " +
            html_escape(algo_display_name(e.value("baseline", ""))) + "</td><td class=\"p\"" + sort_value(p) + ">" +
            (p ? fixed(*p, 2) : "—") + "</td><td>" + interval_text(e.value("ci", nlohmann::json()), 2) + "</td><td>" +
            std::to_string(e.value("n_x", 0)) + " vs " + std::to_string(e.value("n_y", 0)) + "</td></tr>\n";
  }
  return html + "</tbody></table>\n";
}

std::string iqm_table(const ReportFolder& folder) {
  const nlohmann::json entries = folder.summary.value("aggregate_iqm", nlohmann::json::array());
  if (entries.empty()) return "";
  const int decimals = table_decimals_of(folder.summary);
  std::string html =
      "<h3>IQM over all cells</h3>\n<p>Interquartile mean of every ok run of an algorithm, pooled over its cells "
      "(95% stratified-bootstrap interval). Returns are not normalised across scenarios: read it next to Table I.</p>\n"
      "<table class=\"sortable numbers\" id=\"iqm-table\">" +
      header({"Algorithm", "IQM", "95% interval", "Runs", "Cells"}) + "<tbody>\n";
  std::size_t order = 0;
  for (const nlohmann::json& e : entries) {
    const std::optional<double> iqm = optional_number(e, "iqm");
    html += "<tr data-order=\"" + std::to_string(order++) + "\"><td>" + html_escape(algo_display_name(e.value("algo", ""))) +
            "</td><td" + sort_value(iqm) + ">" + (iqm ? fixed(*iqm, decimals) : "—") + "</td><td>" +
            interval_text(e.value("ci", nlohmann::json()), decimals) + "</td><td data-sort=\"" +
            std::to_string(e.value("n_runs", 0)) + "\">" + std::to_string(e.value("n_runs", 0)) + "</td><td data-sort=\"" +
            std::to_string(e.value("n_cells", 0)) + "\">" + std::to_string(e.value("n_cells", 0)) + "</td></tr>\n";
  }
  return html + "</tbody></table>\n";
}

// summary.json's "run_costs" (absent before summaries had them): per scenario the median wall time of
// an algorithm's ok run with its range, as table.md's "What a run cost".
std::string run_cost_table(const ReportFolder& folder) {
  const nlohmann::json costs = folder.summary.value("run_costs", nlohmann::json::array());
  if (costs.empty()) return "";
  const auto has_cost = [&](const std::string& key, const std::string& value) {
    return std::any_of(costs.begin(), costs.end(), [&](const nlohmann::json& c) { return c.value(key, "") == value; });
  };
  std::vector<std::string> algos, scenarios;  // Table I's columns and the grid's scenarios that have a cost
  for (const std::string& a : table_columns(folder.summary))
    if (has_cost("algo", a)) algos.push_back(a);
  for (const std::string& sc : folder.summary["grid"].value("scenarios", std::vector<std::string>{}))
    if (has_cost("scenario", sc)) scenarios.push_back(sc);
  std::vector<std::string> columns = {"Scenario"};
  for (const std::string& a : algos) columns.push_back(algo_display_name(a));
  std::string html =
      "<h3>What a run cost</h3>\n<p>Wall time of one ok run in seconds, start to end: the median over the "
      "scenario's cells and seeds, [fastest, slowest], with whatever else the machine ran.</p>\n"
      "<table class=\"numbers\" id=\"run-cost-table\">" + header(columns) + "<tbody>\n";
  for (const std::string& scenario : scenarios) {
    html += "<tr><td>" + html_escape(scenario_display_name(scenario)) + "</td>";
    for (const std::string& a : algos) {
      const auto it = std::find_if(costs.begin(), costs.end(), [&](const nlohmann::json& c) {
        return c.value("scenario", "") == scenario && c.value("algo", "") == a;
      });
      html += "<td>" +
              (it == costs.end() ? std::string("—")
                                 : run_cost_text(it->value("median_s", 0.0), it->value("min_s", 0.0), it->value("max_s", 0.0))) +
              "</td>";
    }
    html += "</tr>\n";
  }
  return html + "</tbody></table>\n";
}

// The paper's order of the methods beside ours, row by row (paper_ranking.hpp); nothing when the
// grid has no row of the paper's Table I.
std::string paper_beside(const ReportFolder& folder) {
  const std::optional<PaperAgreement> agreement = paper_agreement(our_rows(folder.summary));
  if (!agreement) return "";
  std::string html = "<section id=\"paper-beside\"><h2>The paper beside us</h2>\n<p>" + html_escape(paper_agreement_preamble()) +
                     "</p>\n<table class=\"sortable numbers\" id=\"paper-beside-table\">" +
                     header({"Scenario", "Dataset", "The paper's order", "Our order", "τ", "95% interval", "Same best"}) +
                     "<tbody>\n";
  std::size_t index = 0;
  for (const RowAgreement& r : agreement->rows) {
    const RowTexts text = row_texts(r);
    html += "<tr data-order=\"" + std::to_string(index++) + "\"><td>" + html_escape(scenario_display_name(r.scenario)) +
            "</td><td>" + html_escape(dataset_display_name(r.dataset)) + "</td><td>" + html_escape(text.paper_order) +
            "</td><td>" + html_escape(text.our_order) + "</td><td" + sort_value(r.tau) + ">" + fixed(r.tau, 2) +
            "</td><td>" + html_escape(text.tau_interval) + "</td><td>" + (r.same_best ? "yes" : "no") + "</td></tr>\n";
  }
  return html + "</tbody></table>\n<p>" + html_escape(paper_agreement_conclusion(*agreement)) + "</p></section>\n";
}

}  // namespace

std::string tables_section(const ReportFolder& folder) {
  return "<section id=\"table-i\"><h2>Table I: final return</h2>\n<p>Mean ± population std over the ok seeds of each "
         "run's final return; <code>(n=ok/expected)</code> when seeds are short, — without an ok seed. The best mean of a "
         "row is <strong>bold</strong>. DDPG takes no dataset: its cell repeats in every dataset row. Click a column "
         "header to sort by it (again to reverse), a cell for its seeds.</p>\n" +
         table_i(folder) + "</section>\n" + paper_beside(folder) +
         "<section id=\"poi\"><h2>Probability of improvement</h2>\n<p>P(X &gt; Y) per row over the ok seeds: "
         "Mann–Whitney U / (n<sub>X</sub>·n<sub>Y</sub>), ties count half; 95% interval from a stratified bootstrap. "
         "RAPID-RL against each of the paper's baselines, and each variant the paper does not have against "
         "RAPID-RL.</p>\n" +
         poi_table(folder) + poi_plot(folder) + iqm_table(folder) + iqm_plot(folder) + profiles(folder) + run_cost_table(folder) + "</section>\n";
}

}  // namespace rapid::report_page
