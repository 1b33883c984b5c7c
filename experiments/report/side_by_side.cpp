#include "experiments/report/side_by_side.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "experiments/report/format.hpp"
#include "experiments/report/summary.hpp"
#include "experiments/run/json_numbers.hpp"

namespace rapid {

namespace {

using nlohmann::json;

bool has_axis(const json& j) { return j.contains("axis") && !j["axis"].empty(); }

// One summary's Table I without axis rows (a tuned grid has none): row "scenario/dataset" → algo →
// its cell, and the rows and algorithms in the summary's order.
struct Table {
  std::vector<std::pair<std::string, std::string>> rows;  // (scenario, dataset)
  std::vector<std::string> algos;                         // the table's columns, in their order
  std::map<std::string, std::map<std::string, json>> cells;
  std::map<std::string, json> iqm;                        // algo → aggregate_iqm entry
};

Table table_of(const json& summary) {
  Table t;
  std::map<std::string, json> cell_by_key;
  for (const json& cell : summary.at("cells")) {
    if (has_axis(cell)) continue;
    cell_by_key[summary_cell_key(cell)] = cell;
  }
  for (const json& row : summary.at("table")) {
    if (has_axis(row) || !row.at("dataset").is_string()) continue;
    const std::string scenario = row.at("scenario").get<std::string>(), dataset = row["dataset"].get<std::string>();
    t.rows.emplace_back(scenario, dataset);
    for (const json& column : row.at("columns")) {
      const std::string algo = column.at("algo").get<std::string>();
      if (std::find(t.algos.begin(), t.algos.end(), algo) == t.algos.end()) t.algos.push_back(algo);
      if (const auto it = cell_by_key.find(column.at("cell").get<std::string>()); it != cell_by_key.end())
        t.cells[scenario + "/" + dataset][algo] = it->second;
    }
  }
  for (const json& entry : summary.value("aggregate_iqm", json::array())) t.iqm[entry.at("algo").get<std::string>()] = entry;
  return t;
}

const json* find_cell(const Table& t, const std::string& row, const std::string& algo) {
  const auto r = t.cells.find(row);
  if (r == t.cells.end()) return nullptr;
  const auto c = r->second.find(algo);
  return c == r->second.end() ? nullptr : &c->second;
}

std::string iqm_text(const json* entry) {
  if (entry == nullptr || !optional_number(*entry, "iqm")) return "—";
  std::string text = fixed(entry->at("iqm").get<double>(), 1);
  if (entry->contains("ci") && entry->at("ci").is_array() && entry->at("ci").size() == 2)
    text += " [" + fixed(entry->at("ci")[0].get<double>(), 1) + ", " + fixed(entry->at("ci")[1].get<double>(), 1) + "]";
  return text;
}

// A comparison's identity across two reports: where, metric and the two sides.
std::string comparison_id(const json& c) {
  return c.at("where").get<std::string>() + " | " + c.at("metric").get<std::string>() + " | " +
         c.at("x").get<std::string>() + " vs " + c.at("y").get<std::string>();
}

std::string outcome_text(const json& c) {
  const std::string outcome = c.at("outcome").get<std::string>();
  if (outcome == "x better") return c.at("x").get<std::string>() + " higher";
  if (outcome == "y better") return c.at("y").get<std::string>() + " higher";
  if (outcome == "equivalent") return "within ±δ";
  return outcome;
}

void write_claims(std::ostringstream& md, const json& now, const json& before, const std::string& now_label,
                  const std::string& before_label) {
  md << "## The claims, decided\n\n";
  const bool have_now = now.contains("decisions") && now["decisions"].is_object();
  const bool have_before = before.contains("decisions") && before["decisions"].is_object();
  if (!have_now || !have_before) {
    md << (have_now ? before_label : now_label) << " has no decided verdicts (its profile has no decision rule): "
       << "nothing to set side by side.\n\n";
    return;
  }
  std::map<std::string, json> earlier;
  for (const json& claim : before["decisions"].at("claims")) earlier[claim.at("id").get<std::string>()] = claim;
  md << "| claim | " << now_label << " | " << before_label << " | " << now_label << ": why |\n|---|---|---|---|\n";
  int changed = 0;
  for (const json& claim : now["decisions"].at("claims")) {
    const std::string id = claim.at("id").get<std::string>(), verdict = claim.at("verdict").get<std::string>();
    const auto it = earlier.find(id);
    const std::string was = it == earlier.end() ? "—" : it->second.at("verdict").get<std::string>();
    if (was != verdict) ++changed;
    md << "| " << markdown_text(id) << " | " << (was != verdict ? "**" + markdown_text(verdict) + "**" : markdown_text(verdict))
       << " | " << markdown_text(was) << " | " << markdown_text(claim.at("reason").get<std::string>()) << " |\n";
  }
  md << "\n" << changed << " verdict" << (changed == 1 ? "" : "s") << " changed (in bold).\n\n";
}

void write_baselines(std::ostringstream& md, const json& now, const json& before, const std::string& now_label,
                     const std::string& before_label) {
  const bool have_now = now.contains("baseline_decisions") && now["baseline_decisions"].is_object();
  if (!have_now) return;
  md << "## RAPID-RL against the baselines the paper does not run\n\n";
  std::map<std::string, json> earlier;
  if (before.contains("baseline_decisions") && before["baseline_decisions"].is_object())
    for (const json& c : before["baseline_decisions"].at("comparisons")) earlier[comparison_id(c)] = c;
  std::vector<std::string> lines;
  int same = 0, total = 0;
  for (const json& c : now["baseline_decisions"].at("comparisons")) {
    ++total;
    const auto it = earlier.find(comparison_id(c));
    const std::string was = it == earlier.end() ? "not compared" : outcome_text(it->second);
    const std::string is = outcome_text(c);
    if (was == is) {
      ++same;
      continue;
    }
    lines.push_back("| " + markdown_text(c.at("where").get<std::string>()) + " | " + markdown_text(c.at("x").get<std::string>()) +
                    " vs " + markdown_text(c.at("y").get<std::string>()) + " | " + markdown_text(is) + " | " + markdown_text(was) + " | " +
                    short_number(optional_number(c, "p_difference")) + " |");
  }
  const auto family_size = [](const json& summary) {
    const json& d = summary.value("baseline_decisions", json());
    return d.is_object() && d.contains("family_size") ? std::to_string(d["family_size"].get<long>()) : std::string("no");
  };
  md << "Each report's comparisons are a Holm family of their own (" << now_label << ": " << family_size(now)
     << " hypotheses, " << before_label << ": " << family_size(before) << "). " << same << " of " << total << " comparisons have the same outcome in both";
  if (lines.empty()) {
    md << ".\n\n";
    return;
  }
  md << "; the others:\n\n| where | comparison | " << now_label << " | " << before_label << " | p (difference), "
     << now_label << " |\n|---|---|---|---|---:|\n";
  for (const std::string& line : lines) md << line << "\n";
  md << "\n";
}

}  // namespace

std::string side_by_side_markdown(const json& now, const std::string& now_name, const json& before,
                                  const std::string& before_name) {
  // The labels are a user's (--labels) or a folder's name: text, never markup (issue #67).
  const std::string now_label = markdown_text(now_name), before_label = markdown_text(before_name);
  const Table a = table_of(now), b = table_of(before);
  const bool shared = std::any_of(a.rows.begin(), a.rows.end(), [&](const auto& row) {
    return b.cells.count(row.first + "/" + row.second) > 0;
  });
  if (!shared) throw std::invalid_argument("the two reports have no Table I row in common");

  double magnitude = 0.0;
  for (const auto& [row, cells] : a.cells)
    for (const auto& [algo, cell] : cells)
      if (const auto m = optional_number(cell, "mean")) magnitude = std::max(magnitude, std::abs(*m));
  const int decimals = table_decimals(magnitude);

  std::ostringstream md;
  md << "# " << now_label << " beside " << before_label << "\n\n";
  md << "## Table I\n\nFinal return, mean ± std over the ok seeds of " << now_label << "; in brackets the mean of the "
     << "same cell in " << before_label << " (—: not there).\n\n| Scenario | Dataset |";
  for (const std::string& algo : a.algos) md << " " << algo_display_name(algo) << " |";
  md << "\n|---|---|";
  for (std::size_t i = 0; i < a.algos.size(); ++i) md << "---:|";
  md << "\n";
  for (const auto& [scenario, dataset] : a.rows) {
    const std::string row = scenario + "/" + dataset;
    md << "| " << scenario_display_name(scenario) << " | " << dataset_display_name(dataset) << " |";
    for (const std::string& algo : a.algos) {
      const json* cell = find_cell(a, row, algo);
      const json* earlier = find_cell(b, row, algo);
      std::string text = "—";
      if (cell != nullptr)
        text = table_cell_text(optional_number(*cell, "mean"), optional_number(*cell, "std"), cell->at("n_ok").get<int>(),
                               cell->at("n_expected").get<int>(), decimals, " ± ", "—");
      const std::optional<double> was = earlier == nullptr ? std::nullopt : optional_number(*earlier, "mean");
      md << " " << text << " (" << (was ? fixed(*was, decimals) : "—") << ") |";
    }
    md << "\n";
  }

  md << "\n## IQM per algorithm over all cells\n\nInterquartile mean of every ok run's final return, 95% "
     << "stratified-bootstrap interval (as table.md).\n\n| Algorithm | " << now_label << " | " << before_label
     << " |\n|---|---:|---:|\n";
  for (const std::string& algo : a.algos) {
    const auto now_it = a.iqm.find(algo), before_it = b.iqm.find(algo);
    md << "| " << algo_display_name(algo) << " | " << iqm_text(now_it == a.iqm.end() ? nullptr : &now_it->second)
       << " | " << iqm_text(before_it == b.iqm.end() ? nullptr : &before_it->second) << " |\n";
  }
  md << "\n";
  write_claims(md, now, before, now_label, before_label);
  write_baselines(md, now, before, now_label, before_label);
  return md.str();
}

}  // namespace rapid
