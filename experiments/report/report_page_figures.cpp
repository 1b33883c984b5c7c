// report.html's figures: scripts/plot's PNGs inlined (data URIs), each with what it shows, and a
// note for a figure the folder does not have; then links to the animations of the best and
// worst cells.
#include <map>

#include "experiments/report/html_text.hpp"
#include "experiments/report/report_page_sections.hpp"

namespace rapid::report_page {

namespace {

std::string caption(const std::string& name) {
  static const std::map<std::string, std::string> captions = {
      {"figure2", "Figure 2: evaluation return against env steps, seed mean (line) ± one std (band), one panel per "
                  "scenario × dataset; the legend gives each cell's ok-seed count."},
      {"figure3a", "Figure 3(a): reward per step in each prior dataset (share of its transitions per bin), ε as a "
                   "dotted line."},
      {"figure3b", "Figure 3(b): RAPID-RL's imitation losses on the prior (solid) and online (dotted) halves of its "
                   "batches, seed mean ± one std."}};
  const auto it = captions.find(name);
  if (it != captions.end()) return it->second;
  const std::string key = name.substr(std::string("sensitivity-").size());
  return "Sensitivity to <code>" + html_escape(key) +
         "</code>: final return against the axis value, 95% interval as a band; an algorithm that does not read the "
         "axis is dashed and flat.";
}

}  // namespace

std::string figures_section(const ReportFolder& folder) {
  std::string html = "<section id=\"figures\"><h2>Figures</h2>\n";
  std::map<std::string, bool> drawn;
  for (const Figure& f : folder.figures) {
    drawn[f.name] = true;
    html += "<figure id=\"" + html_escape(f.name) + "\"><img class=\"figure\" alt=\"" + html_escape(f.name) + "\" src=\"" +
            f.data_uri + "\"><figcaption>" + caption(f.name) + "</figcaption></figure>\n";
  }
  std::vector<std::string> expected = {"figure2", "figure3a", "figure3b"};
  for (const GridAxis& axis : folder.sweep.grid.axes) expected.push_back("sensitivity-" + axis.key);
  for (const std::string& name : expected)
    if (!drawn.count(name))
      html += "<p class=\"missing\">" + html_escape(name) +
              ": not drawn (no " + html_escape(name) + ".png in the reports folder; scripts/plot needs Debian's "
              "python3-matplotlib).</p>\n";
  if (!folder.animations.empty()) {
    html += "<h3>Animations</h3>\n<p>One evaluation episode of each driving scenario's best and worst cell "
            "(docs/traces.md):</p>\n<ul>\n";
    for (const std::string& gif : folder.animations)
      html += "<li><a href=\"" + html_escape(gif) + "\">" + html_escape(gif) + "</a></li>\n";
    html += "</ul>\n";
  }
  return html + "</section>\n";
}

}  // namespace rapid::report_page
