// report.html's drill-down: per cell of summary.json, its statistics, every seed's evaluation
// curve (runs.csv) and a table of its seeds: status, final return, error, and links to the
// record and to the animation drawn from the run, where those files are.
#include <algorithm>
#include <map>

#include "experiments/report/format.hpp"
#include "experiments/report/html_text.hpp"
#include "experiments/report/report_page_sections.hpp"
#include "experiments/report/summary.hpp"
#include "experiments/report/seed_curves_svg.hpp"
#include "experiments/report/summary_svg.hpp"

namespace rapid::report_page {

namespace {

// Where the records are, said once above the cells.
std::string records_note(const ReportFolder& folder) {
  std::string note;
  if (folder.records_present == 0)
    note = "The run records are not in this folder (a committed reports folder: <code>jobs/</code> is not in git); "
           "each seed names where its <code>record.json</code> is in the full sweep folder. ";
  if (!folder.has_runs_csv) note += "There is no runs.csv here, so no seed's curve is drawn. ";
  return note.empty() ? "" : "<p class=\"note\">" + note + "</p>\n";
}

std::string statistics_line(const nlohmann::json& cell, int decimals) {
  const auto value = [&](const char* key) { return optional_number(cell, key); };
  std::string statuses;
  const nlohmann::json counts = cell.value("statuses", nlohmann::json::object());
  for (const auto& [status, n] : counts.items())
    statuses += (statuses.empty() ? "" : ", ") + html_value(n) + " " + html_escape(status);
  std::string html = "<p>Seeds: " + statuses + ". Mean " + (value("mean") ? fixed(*value("mean"), decimals) : "—") +
                     " " + interval_text(cell.value("mean_ci", nlohmann::json()), decimals) + ", IQM " +
                     (value("iqm") ? fixed(*value("iqm"), decimals) : "—") + " " +
                     interval_text(cell.value("iqm_ci", nlohmann::json()), decimals) +
                     " (95% bootstrap intervals), area under the mean curve / step range " +
                     (value("eval_auc") ? fixed(*value("eval_auc"), decimals) : "—") + ".</p>\n";
  return html;
}

std::string seed_row(const nlohmann::json& seed, const std::string& colour, const SeedFiles* files, int decimals) {
  const std::string status = seed.value("status", "");
  const std::optional<double> final = optional_number(seed, "final");
  std::string html = "<tr data-seed=\"" + html_value(seed.value("seed", nlohmann::json(0))) + "\"><td><span class=\"swatch\" style=\"background:" +
                     colour + "\"></span>" + html_value(seed.value("seed", nlohmann::json(0))) + "</td><td class=\"status status-" +
                     html_escape(status) + "\">" + html_escape(status) + "</td><td class=\"final\" data-sort=\"" +
                     exact_number(final) + "\">" + (final ? fixed(*final, decimals) : "—") + "</td><td>";
  if (files && files->record_present)
    html += "<a href=\"" + html_escape(files->record) + "\">record.json</a>";
  else if (files)
    html += "<code class=\"absent\" title=\"not in this folder\">" + html_escape(files->record) + "</code>";
  html += "</td><td>";
  if (files && !files->animation.empty())
    html += "<a href=\"" + html_escape(files->animation) + "\">" + html_escape(files->animation) + "</a>";
  const nlohmann::json error = seed.value("error", nlohmann::json());
  return html + "</td><td>" + (error.is_string() ? html_escape(error.get<std::string>()) : "") + "</td></tr>\n";
}

// Every ok seed's final return as a dot beside the cell's mean ± std, coloured as its row below.
std::string seed_dots(const nlohmann::json& cell, const std::map<std::uint64_t, std::string>& colours,
                      std::pair<double, double> range) {
  std::vector<SeedDot> dots;
  for (const nlohmann::json& seed : cell.value("seeds", nlohmann::json::array()))
    if (seed.value("status", "") == "ok")
      if (const std::optional<double> f = optional_number(seed, "final")) {
        const std::uint64_t s = seed.value("seed", std::uint64_t{0});
        dots.push_back({"seed " + std::to_string(s), *f, colours.at(s)});
      }
  const std::string svg = seed_dots_svg(dots, optional_number(cell, "mean"),
                                        optional_number(cell, "std"), range);
  return svg.empty() ? "" : "<figure class=\"dots-figure\">" + svg + "<figcaption>Final return of every ok seed (dots) "
                            "beside the mean (tick) ± std (bar), on the scenario's range.</figcaption></figure>\n";
}

std::string cell_details(const ReportFolder& folder, const nlohmann::json& cell, std::size_t index, int decimals,
                         std::pair<double, double> range) {
  const std::string key = summary_cell_key(cell, folder.sweep.grid.axes);
  const auto files = folder.seed_files.find(key);
  const auto curves = folder.seed_curves.find(key);
  const nlohmann::json seeds = cell.value("seeds", nlohmann::json::array());
  std::map<std::uint64_t, std::string> colours;
  for (std::size_t i = 0; i < seeds.size(); ++i) colours[seeds[i].value("seed", std::uint64_t{0})] = seed_colour(i);

  const std::string point = axis_text(cell.value("axis", nlohmann::json()));
  std::string html = "<details class=\"cell-detail\" id=\"" + cell_anchor(index) + "\" data-cell=\"" + html_escape(key) +
                     "\"><summary>" + html_escape(row_label(cell.value("scenario", ""), cell.value("dataset", nlohmann::json()))) +
                     " / " + html_escape(algo_display_name(cell.value("algo", ""))) +
                     (point.empty() ? "" : " (" + html_escape(point) + ")") + ": " +
                     html_escape(table_cell_text(optional_number(cell, "mean"), optional_number(cell, "std"), cell.value("n_ok", 0),
                                                 cell.value("n_expected", 0), decimals, " ± ", "—")) +
                     "</summary>\n<div class=\"drill\">\n" + statistics_line(cell, decimals) +
                     seed_dots(cell, colours, range);
  const std::string svg = curves == folder.seed_curves.end() ? "" : seed_curves_svg(curves->second, colours);
  html += svg.empty() ? "<p class=\"note\">No seed of this cell has an evaluation curve in runs.csv.</p>\n"
                      : "<figure class=\"seeds-figure\">" + svg + "<figcaption>Evaluation return of every ok seed against "
                        "env steps (one line per seed, coloured as in the table).</figcaption></figure>\n";
  html += "<table class=\"seeds numbers\"><thead><tr><th>Seed</th><th>Status</th><th>Final return</th><th>Record</th>"
          "<th>Animation</th><th>Error</th></tr></thead><tbody>\n";
  for (const nlohmann::json& seed : seeds) {
    const std::uint64_t s = seed.value("seed", std::uint64_t{0});
    const SeedFiles* f = nullptr;
    if (files != folder.seed_files.end())
      if (const auto it = files->second.find(s); it != files->second.end()) f = &it->second;
    html += seed_row(seed, colours[s], f, decimals);
  }
  return html + "</tbody></table>\n</div></details>\n";
}

}  // namespace

std::string cells_section(const ReportFolder& folder) {
  const int decimals = table_decimals_of(folder.summary);
  std::string html = "<section id=\"cells\"><h2>Cells and seeds</h2>\n" + records_note(folder);
  const nlohmann::json& cells = folder.summary["cells"];
  std::map<std::string, std::pair<double, double>> range;  // scenario → lowest and highest ok final
  for (const nlohmann::json& cell : cells)
    for (const nlohmann::json& seed : cell.value("seeds", nlohmann::json::array()))
      if (const std::optional<double> f = optional_number(seed, "final"); f && seed.value("status", "") == "ok") {
        const auto [it, added] = range.try_emplace(cell.value("scenario", ""), *f, *f);
        it->second = {std::min(it->second.first, *f), std::max(it->second.second, *f)};
      }
  for (std::size_t i = 0; i < cells.size(); ++i)
    html += cell_details(folder, cells[i], i, decimals, range[cells[i].value("scenario", "")]);
  return html + "</section>\n";
}

}  // namespace rapid::report_page
