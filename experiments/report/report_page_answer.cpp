// report.html's first section: what the grid answers, before any table. Each claim's verdict with
// its reason in a sentence and, for an undecided one, what deciding it would take; the method with
// the highest mean per row (labelled: a point mean, not a decision); and RAPID-RL against the
// baselines the paper does not run, where the grid has them. Everything comes from summary.json.
#include <algorithm>
#include <map>

#include "experiments/report/format.hpp"
#include "experiments/report/html_text.hpp"
#include "experiments/report/report_page_sections.hpp"

namespace rapid::report_page {

namespace {

using nlohmann::json;

// "7 comparisons undecided; the nearest needs about 51 seeds per algorithm", from the claim's
// comparisons in the decisions' list; "—" for a decided claim.
std::string to_decide(const json& decisions, const json& claim) {
  if (claim.value("verdict", "") != "UNDECIDED") return "—";
  const json& comparisons = decisions.value("comparisons", json::array());
  int undecided = 0;
  std::optional<long> nearest;
  for (const json& index : claim.value("comparisons", json::array())) {
    if (!index.is_number_unsigned() || index.get<std::size_t>() >= comparisons.size()) continue;
    const json& c = comparisons[index.get<std::size_t>()];
    if (c.value("outcome", "") != "undecided") continue;
    ++undecided;
    if (c.contains("seeds_needed") && c["seeds_needed"].is_number())
      nearest = std::min(nearest.value_or(c["seeds_needed"].get<long>()), c["seeds_needed"].get<long>());
  }
  return std::to_string(undecided) + " comparison" + (undecided == 1 ? "" : "s") + " undecided" +
         (nearest ? "; the nearest needs about " + std::to_string(*nearest) + " seeds per algorithm" : "");
}

std::string claims_table(const json& summary) {
  if (summary.contains("decisions")) {
    const json& d = summary["decisions"];
    std::string html =
        "<p>The paper's claims, decided on the per-seed numbers at a family-wise error of α = " +
        short_number(optional_number(d, "alpha")) +
        " (docs/decisions.md). CONFIRMED: the claim holds even if every undecided comparison went against it; "
        "REFUTED: it fails even if every undecided comparison went for it.</p>\n<table class=\"answer\" id=\"answer-claims\">"
        "<thead><tr><th>Claim</th><th>The paper says</th><th>Verdict</th><th>Why</th><th>To decide it</th></tr></thead><tbody>\n";
    for (const json& c : d.value("claims", json::array()))
      html += "<tr><td>" + html_escape(c.value("id", "")) + "</td><td>" + html_escape(statement_of(summary.value("claims", json::array()), c.value("id", ""))) +
              "</td>" + verdict_cell(c.value("verdict", "")) + "<td>" + html_escape(c.value("reason", "")) + "</td><td>" +
              html_escape(to_decide(d, c)) + "</td></tr>\n";
    return html + "</tbody></table>\n";
  }
  if (!summary.contains("claims") || summary["claims"].empty()) return "";
  std::string html =
      "<p>The paper's claims on the means alone: this summary has no decided verdicts (a grid of the short profile, or a "
      "summary written before they existed), so PASS and FAIL here are not decisions.</p>\n<table class=\"answer\" "
      "id=\"answer-claims\"><thead><tr><th>Claim</th><th>The paper says</th><th>Point means</th><th>Why</th></tr></thead><tbody>\n";
  for (const json& c : summary["claims"])
    html += "<tr><td>" + html_escape(c.value("id", "")) + "</td><td>" + html_escape(c.value("statement", "")) + "</td>" +
            verdict_cell(c.value("verdict", "")) + "<td>" + html_escape(c.value("reason", "")) + "</td></tr>\n";
  return html + "</tbody></table>\n";
}

// One line per scenario: each dataset's method with the highest mean final return.
std::string best_per_row(const json& summary) {
  std::vector<std::string> scenarios;
  std::map<std::string, std::string> lines;
  for (const json& row : summary.value("table", json::array())) {
    const std::string scenario = row.value("scenario", "");
    if (!lines.count(scenario)) scenarios.push_back(scenario);
    const std::string best = row.contains("best") && row["best"].is_string() ? algo_display_name(row["best"]) : "—";
    std::string& line = lines[scenario];
    line += (line.empty() ? "" : " · ") + html_escape(row.value("dataset", "")) +
            (row.contains("axis") ? " (" + html_escape(axis_text(row["axis"])) + ")" : "") + ": <b>" + html_escape(best) + "</b>";
  }
  if (scenarios.empty()) return "";
  std::string html = "<p>The highest mean final return per row (a point mean, not a decision; Table I below):</p>\n<ul class=\"answer-best\">\n";
  for (const std::string& s : scenarios) html += "<li>" + html_escape(s) + ": " + lines[s] + "</li>\n";
  return html + "</ul>\n";
}

// RAPID-RL against each baseline the paper does not run: rows decided each way, and undecided.
std::string baselines_line(const json& summary) {
  if (!summary.contains("baseline_decisions")) return "";
  std::vector<std::string> order;
  std::map<std::string, std::map<std::string, int>> counts;  // baseline → outcome → rows
  for (const json& c : summary["baseline_decisions"].value("comparisons", json::array())) {
    const std::string y = c.value("y", "");
    if (!counts.count(y)) order.push_back(y);
    ++counts[y][c.value("outcome", "")];
  }
  std::string html = "<p>Beside the claims, RAPID-RL against the baselines the paper does not run (a family of its own):";
  for (const std::string& y : order) {
    const auto& n = counts[y];
    const auto get = [&](const char* k) { return n.count(k) ? n.at(k) : 0; };
    html += " against " + html_escape(y) + ", " + std::to_string(get("x better")) + " rows decided for RAPID-RL, " +
            std::to_string(get("y better")) + " for " + html_escape(y) + ", " + std::to_string(get("equivalent")) +
            " equivalent and " + std::to_string(get("undecided")) + " undecided;";
  }
  html.back() = '.';
  return html + "</p>\n";
}

// The aggregate claims first (docs/confirmatory.md): each contrast's estimate in δ units, its
// interval's ends are in claims.md; here the outcome, the estimate and both p-values.
std::string aggregate_table(const json& summary) {
  if (!summary.contains("aggregate_decisions")) return "";
  const json& d = summary["aggregate_decisions"];
  const json specs = summary.value("aggregate_claims", json::array());
  bool registered = false;
  for (const json& a : specs) registered = registered || a.value("registered", false);
  std::string html = std::string("<p>") + (registered ? "The pre-registered question (docs/confirmatory.md), " : "The aggregate claims, ") +
                     "decided at a family-wise error of α = " + short_number(optional_number(d, "alpha")) +
                     ": per seed, the mean over the rows of the two final returns in δ units, a paired t test for a "
                     "difference and TOST within ±margin. An aggregate over the rows is not the paper's per-row wording; "
                     "the paper's claims follow.</p>\n<table class=\"answer\" id=\"answer-aggregate\"><thead><tr><th>Claim</th>"
                     "<th>Question</th><th>Outcome</th><th>Mean difference (δ)</th><th>p difference</th><th>p equivalence</th>"
                     "<th>Seeds</th></tr></thead><tbody>\n";
  const json& comparisons = d.value("comparisons", json::array());
  for (std::size_t i = 0; i < comparisons.size(); ++i) {
    const json& c = comparisons[i];
    const json spec = i < specs.size() ? specs[i] : json::object();
    const std::string outcome = c.value("outcome", "");
    const std::string said = outcome == "x better"     ? c.value("x", "") + " better"
                             : outcome == "y better"   ? c.value("y", "") + " better"
                             : outcome == "equivalent" ? "equivalent within ±" + short_number(optional_number(c, "delta"))
                                                       : "undecided";
    const std::string where = c.value("where", "");
    html += "<tr><td>" + html_escape(spec.value("id", "")) + "</td><td>" + html_escape(spec.value("statement", "")) + "</td>" +
            verdict_cell(said) + "<td>" + short_number(optional_number(c, "difference")) + "</td><td>" +
            short_number(optional_number(c, "p_difference")) + "</td><td>" + short_number(optional_number(c, "p_equivalence")) +
            "</td><td>" + html_escape(where.substr(where.find(": ") == std::string::npos ? 0 : where.find(": ") + 2)) +
            "</td></tr>\n";
  }
  return html + "</tbody></table>\n";
}

}  // namespace

std::string answer_section(const ReportFolder& folder) {
  const json& summary = folder.summary;
  const std::string body = aggregate_table(summary) + claims_table(summary) + best_per_row(summary) + baselines_line(summary);
  if (body.empty()) return "";
  return "<section id=\"answer\"><h2>The answer</h2>\n" + body + "</section>\n";
}

}  // namespace rapid::report_page
