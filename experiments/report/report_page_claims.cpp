// report.html's claims: the decided verdicts (docs/decisions.md) where summary.json has them,
// then the paper's claims with the point-mean verdict, the exact rule checked, the reason and the
// numbers behind it, as claims.md has them.
#include "experiments/report/adaptive_seeds.hpp"
#include "experiments/report/format.hpp"
#include "experiments/report/html_text.hpp"
#include "experiments/report/report_page_sections.hpp"

namespace rapid::report_page {

std::string verdict_cell(const std::string& verdict) {
  std::string css;
  for (const char c : verdict) css += (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : (c == '/' ? '-' : c);
  return "<td class=\"verdict verdict-" + html_escape(css) + "\">" + html_escape(verdict) + "</td>";
}

std::string statement_of(const nlohmann::json& claims, const std::string& id) {
  for (const nlohmann::json& c : claims)
    if (c.value("id", "") == id) return c.value("statement", "");
  return "";
}

namespace {

std::string p_text(const nlohmann::json& p) {
  const std::optional<double> x = optional_number(p);
  return x ? short_number(x) : "—";
}

// Every comparison of a family of summary.json's (its "comparisons"); the "Wanted" column where the
// family decides claims (the claims' family, not the published baselines').
std::string comparisons_table(const nlohmann::json& d) {
  const nlohmann::json comparisons = d.value("comparisons", nlohmann::json::array());
  const bool wanted = d.contains("claims") && !d["claims"].empty();
  std::string html = "<table class=\"numbers\"><thead><tr><th>#</th><th>Where</th><th>Metric</th><th>X vs Y</th>"
                     "<th>X − Y</th><th>p (difference)</th><th>p (equivalence)</th><th>Outcome</th>" +
                     std::string(wanted ? "<th>Wanted</th>" : "") + "<th>Seeds needed</th></tr></thead><tbody>\n";
  std::size_t index = 0;
  for (const nlohmann::json& c : comparisons) {
    const nlohmann::json needed = c.value("seeds_needed", nlohmann::json());
    html += "<tr><td>" + std::to_string(index++) + "</td><td>" + html_escape(c.value("where", "")) + "</td><td>" +
            html_escape(c.value("metric", "")) + "</td><td>" + html_escape(c.value("x", "")) + " vs " +
            html_escape(c.value("y", "")) + "</td><td>" + short_number(optional_number(c, "difference")) +
            "</td><td>" + p_text(c.value("p_difference", nlohmann::json())) + "</td><td>" +
            p_text(c.value("p_equivalence", nlohmann::json())) + "</td><td>" + html_escape(c.value("outcome", "")) +
            (c.contains("frozen") ? " (" + html_value(c["frozen"]) + ")" : "") + "</td>" + (wanted ? "<td>" + html_escape(c.value("wanted", "")) + "</td>" : "") + "<td>" +
            (needed.is_number() ? html_value(needed) : "—") + "</td></tr>\n";
  }
  return html + "</tbody></table>";
}

std::string decided(const nlohmann::json& summary) {
  if (!summary.contains("decisions")) return "";
  const nlohmann::json& d = summary["decisions"];
  const nlohmann::json claims = summary.value("claims", nlohmann::json::array());
  std::string html =
      "<h3>Decided verdicts</h3>\n<p>Each comparison tested on the per-seed numbers (Welch's t test for a difference, "
      "TOST for equivalence within ±δ), all " +
      std::to_string(d.value("family_size", 0)) + " hypotheses under Holm's procedure at α = " +
      short_number(optional_number(d, "alpha_per_look")) + "; δ: " +
      html_escape(d.value("delta_rule", "")) +
      ".</p>\n<table class=\"claims\" id=\"decided-claims\"><thead><tr><th>Claim</th><th>Statement</th><th>Verdict</th>"
      "<th>Reason</th></tr></thead><tbody>\n";
  for (const nlohmann::json& c : d.value("claims", nlohmann::json::array()))
    html += "<tr><td>" + html_escape(c.value("id", "")) + "</td><td>" +
            html_escape(statement_of(claims, c.value("id", ""))) + "</td>" + verdict_cell(c.value("verdict", "")) +
            "<td>" + html_escape(c.value("reason", "")) + "</td></tr>\n";
  return html + "</tbody></table>\n<details><summary>The comparisons</summary>\n" + comparisons_table(d) + "</details>\n";
}

// RAPID-RL against the baselines the paper does not run: summary.json's "baseline_decisions", a
// Holm family of its own (claims.md says the same).
std::string baselines_decided(const nlohmann::json& summary) {
  if (!summary.contains("baseline_decisions")) return "";
  const nlohmann::json& d = summary["baseline_decisions"];
  return "<h3>Beside the claims: RAPID-RL against the baselines the paper does not run</h3>\n<p>RAPID-RL's final "
         "returns against each in every row, by the same tests as a family of their own: " +
         std::to_string(d.value("family_size", 0)) + " hypotheses under Holm's procedure at α = " +
         short_number(optional_number(d, "alpha_per_look")) +
         ", so the verdicts above are those the grid would get without these baselines.</p>\n" + comparisons_table(d) +
         "\n";
}

// A --decide folder's looks: the verdicts at each, the seeds and cells it added, and the runs
// spent against the fixed designs (summary.json's "adaptive_seeds").
std::string adaptive(const nlohmann::json& summary) {
  if (!summary.contains("adaptive_seeds") || !summary["adaptive_seeds"].is_object()) return "";
  const nlohmann::json& a = summary["adaptive_seeds"];
  std::string html = "<h3>Adaptive seeds</h3>\n<p>The grid's " + std::to_string(a.value("initial_seeds", 0)) +
                     " seeds, then blocks of " + std::to_string(a.value("block", 0)) +
                     " seeds for the cells of undecided comparisons only, up to " +
                     std::to_string(a.value("max_seeds", 0)) + " per cell (<code>rapid sweep --decide</code>). " +
                     html_escape(rule_text(a)) + "</p>\n"
                     "<table class=\"numbers\" id=\"adaptive-looks\"><thead><tr><th>Look</th><th>Verdicts</th>"
                     "<th>Seeds added</th><th>Cells</th><th>Frozen</th></tr></thead><tbody>\n";
  for (const nlohmann::json& look : a.value("looks", nlohmann::json::array())) {
    const nlohmann::json added = look.value("added_seeds", nlohmann::json::array());
    const std::size_t cells = look.value("cells", nlohmann::json::array()).size();
    const std::size_t frozen = look.value("frozen", nlohmann::json::array()).size();
    html += "<tr><td>" + std::to_string(look.value("look", 0)) + "</td><td>" + html_escape(look_verdicts_text(look)) +
            "</td><td>" + (added.empty() ? std::string("—") : html_escape(seed_range(added))) +
            "</td><td>" +
            (cells == 0 ? std::string("—")
                        : "<details><summary>" + std::to_string(cells) + "</summary>" +
                              html_escape(look_cells_text(look)) +
                                 "</details>") +
            "</td><td>" +
            (frozen == 0 ? std::string("—")
                         : "<details><summary>" + std::to_string(frozen) + "</summary>" +
                               html_escape(look_frozen_text(look)) + "</details>") +
            "</td></tr>\n";
  }
  const nlohmann::json fixed = a.value("fixed_design_runs", nlohmann::json::object());
  const nlohmann::json stopped = a.value("stopped", nlohmann::json());
  return html + "</tbody></table>\n<p>" +
         html_escape(stopped.is_string() ? "Stopped: " + stopped.get<std::string>() + "." : "The looks have not stopped.") +
         " Runs: " + std::to_string(a.value("runs", 0L)) + " (" + short_number(a.value("run_core_hours", 0.0)) +
         " core-hours), against " + std::to_string(fixed.value("initial", 0L)) + " for the fixed design at the grid's seeds and " +
         std::to_string(fixed.value("max", 0L)) + " at the maximum.</p>\n";
}

std::string claim_numbers(const nlohmann::json& c) {
  const nlohmann::json header = c.value("header", nlohmann::json::array());
  if (header.empty()) return "";
  std::string html = "<table class=\"numbers\"><thead><tr>";
  for (const nlohmann::json& h : header) html += "<th>" + html_escape(h.get<std::string>()) + "</th>";
  html += "</tr></thead><tbody>\n";
  for (const nlohmann::json& row : c.value("rows", nlohmann::json::array())) {
    html += "<tr>";
    for (const nlohmann::json& x : row) html += "<td>" + html_value(x) + "</td>";
    html += "</tr>\n";
  }
  return html + "</tbody></table>\n";
}

std::string point_mean(const nlohmann::json& summary) {
  const nlohmann::json claims = summary.value("claims", nlohmann::json::array());
  if (claims.empty()) return "<p>This summary has no claims check.</p>\n";
  std::string html = "<h3>Point-mean verdicts" + std::string(summary.contains("decisions") ? " (not a decision)" : "") +
                     "</h3>\n<p>Each claim checked on the seed means as stated; N/A where the grid does not hold what "
                     "the claim is about. Open a claim for the rule and its numbers.</p>\n"
                     "<table class=\"claims\" id=\"point-mean-claims\"><thead><tr><th>Claim</th><th>Statement</th>"
                     "<th>Verdict</th><th>Reason</th></tr></thead><tbody>\n";
  for (const nlohmann::json& c : claims)
    html += "<tr><td>" + html_escape(c.value("id", "")) + "</td><td>" + html_escape(c.value("statement", "")) + "</td>" +
            verdict_cell(c.value("verdict", "")) + "<td>" + html_escape(c.value("reason", "")) + "</td></tr>\n";
  html += "</tbody></table>\n";
  for (const nlohmann::json& c : claims)
    html += "<details class=\"claim\"><summary>" + html_escape(c.value("id", "")) + ": " +
            html_escape(c.value("statement", "")) + "</summary>\n<p><strong>Checked:</strong> " +
            html_escape(c.value("definition", "")) + "</p>\n" + claim_numbers(c) + "</details>\n";
  return html;
}

}  // namespace

std::string claims_section(const ReportFolder& folder) {
  return "<section id=\"claims\"><h2>The paper's claims</h2>\n" + decided(folder.summary) +
         baselines_decided(folder.summary) + adaptive(folder.summary) +
         point_mean(folder.summary) +
         "</section>\n";
}

}  // namespace rapid::report_page
