#include "experiments/report/report_page.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/atomic_file.hpp"
#include "experiments/report/format.hpp"
#include "experiments/report/html_text.hpp"
#include "experiments/report/report_page_assets.hpp"
#include "experiments/report/report_page_sections.hpp"

namespace rapid {

namespace fs = std::filesystem;

namespace report_page {

int table_decimals_of(const nlohmann::json& summary) {
  double magnitude = 0.0;
  for (const nlohmann::json& c : summary.value("cells", nlohmann::json::array()))
    if (const auto m = optional_number(c, "mean")) magnitude = std::max(magnitude, std::abs(*m));
  return table_decimals(magnitude);
}

std::string cell_anchor(std::size_t index) { return "cell-" + std::to_string(index); }

std::string interval_text(const nlohmann::json& ci, int decimals) {
  if (!ci.is_array() || ci.size() != 2 || !ci[0].is_number() || !ci[1].is_number()) return "—";
  return "[" + fixed(ci[0].get<double>(), decimals) + ", " + fixed(ci[1].get<double>(), decimals) + "]";
}

std::string row_label(const std::string& scenario, const nlohmann::json& dataset) {
  return scenario_display_name(scenario) + " / " + (dataset.is_string() ? dataset_display_name(dataset) : "—");
}

std::string axis_text(const nlohmann::json& axis) {
  std::string out;
  if (axis.is_object())
    for (const auto& [key, value] : axis.items()) out += (out.empty() ? "" : ", ") + key + " = " + axis_value_label(value);
  return out;
}

namespace {

// "951c49a (390 runs), 46716ac (6 runs)"
std::string counted(const nlohmann::json& counts) {
  std::string out;
  if (counts.is_object())
    for (const auto& [value, n] : counts.items())
      out += (out.empty() ? "" : "; ") + html_escape(value) + " (" + html_value(n) + (n == 1 ? " run)" : " runs)");
  return out.empty() ? "—" : out;
}

std::string fact(const std::string& name, const std::string& html) {
  return "<tr><th scope=\"row\">" + name + "</th><td>" + html + "</td></tr>\n";
}

std::string hours(double seconds) { return fixed(seconds / 3600.0, 2) + " h"; }

std::string joined_names(const nlohmann::json& list, std::string (*display)(const std::string&)) {
  std::string out;
  for (const nlohmann::json& x : list) out += (out.empty() ? "" : ", ") + html_escape(display(x.get<std::string>()));
  return out;
}

std::string grid_facts(const ReportFolder& folder) {
  const nlohmann::json& grid = folder.summary["grid"];
  std::string seeds;
  for (const nlohmann::json& s : grid.value("seeds", nlohmann::json::array())) seeds += (seeds.empty() ? "" : ", ") + html_value(s);
  std::string html = fact("Grid", "<code>" + html_escape(grid.value("name", "")) + "</code>, profile <code>" +
                                      html_escape(folder.sweep.grid.profile) + "</code>");
  if (!folder.sweep.grid.description.empty()) html += fact("Description", html_escape(folder.sweep.grid.description));
  html += fact("Scenarios", joined_names(grid.value("scenarios", nlohmann::json::array()), scenario_display_name));
  html += fact("Datasets", joined_names(grid.value("datasets", nlohmann::json::array()), dataset_display_name));
  html += fact("Algorithms", joined_names(grid.value("algos", nlohmann::json::array()), algo_display_name));
  html += fact("Seeds", seeds);
  for (const GridAxis& axis : folder.sweep.grid.axes) {
    std::string per;
    for (const auto& [scenario, values] : axis.values) {
      std::string list;
      for (const nlohmann::json& v : values) list += (list.empty() ? "" : ", ") + axis_value_label(v);
      per += (per.empty() ? "" : "; ") + scenario_display_name(scenario) + ": " + list;
    }
    html += fact("Axis <code>" + html_escape(axis.key) + "</code>", html_escape(per));
  }
  std::string statuses;
  const nlohmann::json counts = folder.summary.value("status_counts", nlohmann::json::object());
  for (const auto& [status, n] : counts.items())
    statuses += (statuses.empty() ? "" : ", ") + html_value(n) + " " + html_escape(status);
  std::string runs = statuses + " in " + std::to_string(folder.summary["cells"].size()) + " cells";
  if (counts.value("missing", 0) > 0)  // a grid seed without a record: say why one may be missing
    runs += folder.summary.contains("adaptive_seeds")
                ? ". Missing: seeds of the grid this adaptive sweep did not run, since no comparison of their cell "
                  "needed them (<code>--decide</code> adds a cell's seeds only while a comparison needs them; "
                  "docs/decisions.md)"
                : ". Missing: seeds of the grid with no record yet (not run, or their folder was lost)";
  html += fact("Runs", runs);
  return html;
}

// Revision, machine and the runs' summed training time: summary.json's "provenance", taken from
// the records when they were summarised.
std::string record_facts(const ReportFolder& folder) {
  if (!folder.summary.contains("provenance"))
    return fact("Revision, machine",
                "not in this summary.json: it was written before summaries carried the records' provenance (or no "
                "run is ok); <code>rapid summarize</code> on the sweep folder with its records adds them");
  const nlohmann::json& p = folder.summary["provenance"];
  std::string revision = counted(p.value("code_revisions", nlohmann::json::object()));
  if (p.value("dirty_runs", 0) > 0)
    revision += ", " + std::to_string(p.value("dirty_runs", 0)) +
                " of them built with uncommitted changes (the working tree differed from the revision named when "
                "the binary was built, so the revision alone may not rebuild them)";
  std::string html = fact("Code revision", revision);
  html += fact("Machine", counted(p.value("hosts", nlohmann::json::object())));
  html += fact("Compiler", counted(p.value("compilers", nlohmann::json::object())));
  html += fact("Instruction set", counted(p.value("arch_flags", nlohmann::json::object())));
  html += fact("SUMO", counted(p.value("sumo_versions", nlohmann::json::object())));
  html += fact("Training cost", hours(p.value("run_wall_s", 0.0)) + " of run wall time summed over " +
                                    std::to_string(p.value("timed_runs", 0)) + " ok runs (core-hours at one core a run)");
  return html;
}

// What the last `rapid sweep` on the folder did (sweep.json).
std::string manifest_facts(const ReportFolder& folder) {
  if (!folder.manifest) return fact("Last sweep", "no sweep.json in the sweep folder");
  const nlohmann::json& m = *folder.manifest;
  const nlohmann::json jobs = m.value("jobs", nlohmann::json::object());
  const auto text = [&](const char* key) { return html_escape(m.value(key, std::string("?"))); };
  std::string html = text("status") + ", " + text("backend") + " backend, " + std::to_string(m.value("workers", 0)) +
                     " workers, " + text("started") + " to " + text("ended") + " (" + hours(m.value("wall_s", 0.0)) +
                     " wall); ran " + std::to_string(jobs.value("run", 0)) + " of " +
                     std::to_string(jobs.value("in_grid", 0)) + " jobs (" + std::to_string(jobs.value("skipped_done", 0)) +
                     " already done) in " + std::to_string(m.value("attempts", 0)) + " attempts, " +
                     std::to_string(m.value("failures", nlohmann::json::array()).size()) + " failures";
  if (m.contains("only") && m["only"].is_string()) html += ", only <code>" + html_escape(m["only"].get<std::string>()) + "</code>";
  return fact("Last <code>rapid sweep</code>", html);
}

}  // namespace

std::string provenance_section(const ReportFolder& folder) {
  return "<section id=\"provenance\"><h2>Provenance</h2>\n<table class=\"facts\"><tbody>\n" + grid_facts(folder) +
         record_facts(folder) + manifest_facts(folder) + "</tbody></table></section>\n";
}

}  // namespace report_page

std::string report_page_html(const ReportFolder& folder) {
  using namespace report_page;
  // The page is named after its folder: a grid's reports may live in several (paper-flow and
  // paper-flow-decided are both grid paper-flow's), and the grid is named beside it when it differs.
  const std::string grid = folder.summary["grid"].value("name", "");
  const std::string name = folder.name.empty() ? grid : folder.name;
  const std::string of_grid = grid == name ? "" : " (grid <code>" + html_escape(grid) + "</code>)";
  std::string html = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
                     "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>RAPID-RL reports " +
                     html_escape(name) + "</title>\n<style>\n" + report_page_css() + "</style>\n</head>\n<body>\n";
  html += "<header><h1>Reports <code>" + html_escape(name) + "</code>" + of_grid + "</h1>\n<nav><a href=\"#answer\">The answer</a> <a href=\"#provenance\">Provenance</a> "
          "<a href=\"#table-i\">Table I</a> <a href=\"#poi\">P(improvement)</a> <a href=\"#claims\">Claims</a> "
          "<a href=\"#figures\">Figures</a> <a href=\"#cells\">Cells and seeds</a></nav></header>\n<main>\n";
  html += "<pre id=\"selftest\" hidden></pre>\n";
  html += answer_section(folder) + provenance_section(folder) + tables_section(folder) + claims_section(folder) + figures_section(folder) +
          cells_section(folder);
  html += "</main>\n<script>\n" + report_page_script() + "</script>\n</body>\n</html>\n";
  return html;
}

std::uintmax_t write_report_page(const fs::path& report_dir, const fs::path& sweep_dir) {
  const ReportFolder folder = read_report_folder(report_dir, sweep_dir);
  std::string html;
  try {
    html = report_page_html(folder);
  } catch (const nlohmann::json::exception& e) {
    // A field of the wrong type in a hand-edited summary.json, grid.json or sweep.json.
    throw std::invalid_argument((report_dir / "summary.json").string() + " (or its grid.json, sweep.json): a field has "
                                "the wrong type: " + e.what());
  }
  write_file_atomic((report_dir / kReportPage).string(), html);
  return html.size();
}

}  // namespace rapid
