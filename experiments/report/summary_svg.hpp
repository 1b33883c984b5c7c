// The figures rliable draws (Agarwal et al. 2021), as inline SVG for report.html from summary.json's
// numbers: an interval plot (a point and its 95% interval per row: the probability of improvement
// per comparison, the IQM per algorithm) and performance profiles (per algorithm, the share of its
// runs whose final return is above each level). No script and no network: the page shows them as
// written, and they are the same bytes on every machine.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace rapid {

struct IntervalRow {
  std::string label;  // plain text; escaped here
  std::optional<double> point, lo, hi;
  std::string colour;  // a CSS colour
};

// An <svg class="interval-plot CSS_CLASS"> with one row per entry (a line from lo to hi and a dot
// at the point; a row without a point is labelled only), a dashed line at `reference` when given,
// and the x range `range` when given (else the rows' own, padded). Empty for no rows.
std::string interval_plot_svg(const std::vector<IntervalRow>& rows, const std::string& css_class, const std::string& x_label,
                              std::optional<double> reference = std::nullopt,
                              std::optional<std::pair<double, double>> range = std::nullopt);

struct ProfileSeries {
  std::string label;
  std::string colour;
  std::vector<double> finals;  // one per run
};

// An <svg class="profile"> with one step line per series: the share of its runs whose final return
// is above τ, against τ over the series' range. Series without runs are left out; empty for none.
std::string performance_profile_svg(const std::vector<ProfileSeries>& series, const std::string& title);

struct SeedDot {
  std::string label;   // "seed 3"; escaped here
  double value = 0.0;  // its final return
  std::string colour;
};

// An <svg class="seed-dots"> strip: every seed's final return as a dot (class "seed", coloured as
// the cell's seed table) beside a bar of mean ± std with a tick at the mean, on the x range
// `range` (the scenario's, so strips of one scenario line up). Empty for no dots.
std::string seed_dots_svg(const std::vector<SeedDot>& dots, std::optional<double> mean, std::optional<double> std,
                          std::pair<double, double> range);

// A matplotlib colour name as summary.json carries it ("tab:red") in CSS hex; other names as given.
std::string css_colour(const std::string& matplotlib_name);

}  // namespace rapid
