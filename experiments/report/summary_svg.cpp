#include "experiments/report/summary_svg.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "experiments/report/format.hpp"
#include "experiments/report/html_text.hpp"

namespace rapid {

namespace {

// Coordinates with one decimal: enough on screen, and the same text on every machine.
std::string at(double x) { return fixed(x, 1); }

std::string text(double x, double y, const std::string& anchor, const std::string& content, const std::string& extra = "") {
  return "<text x=\"" + at(x) + "\" y=\"" + at(y) + "\" text-anchor=\"" + anchor + "\"" + extra + ">" + content + "</text>";
}

}  // namespace

std::string css_colour(const std::string& name) {
  static const std::map<std::string, std::string> kTableau = {
      {"tab:blue", "#1f77b4"},  {"tab:orange", "#ff7f0e"}, {"tab:green", "#2ca02c"}, {"tab:red", "#d62728"},
      {"tab:purple", "#9467bd"}, {"tab:brown", "#8c564b"}, {"tab:pink", "#e377c2"},  {"tab:gray", "#7f7f7f"},
      {"tab:olive", "#bcbd22"}, {"tab:cyan", "#17becf"}};
  const auto it = kTableau.find(name);
  return it == kTableau.end() ? name : it->second;
}

std::string interval_plot_svg(const std::vector<IntervalRow>& rows, const std::string& css_class, const std::string& x_label,
                              std::optional<double> reference, std::optional<std::pair<double, double>> range) {
  if (rows.empty()) return "";
  constexpr double kLeft = 250, kRight = 16, kTop = 8, kRow = 16, kBottom = 34, kWidth = 640;
  double x0 = INFINITY, x1 = -INFINITY;
  if (range) {
    x0 = range->first, x1 = range->second;
  } else {
    for (const IntervalRow& r : rows)
      for (const std::optional<double>& v : {r.point, r.lo, r.hi})
        if (v && std::isfinite(*v)) x0 = std::min(x0, *v), x1 = std::max(x1, *v);
    if (reference) x0 = std::min(x0, *reference), x1 = std::max(x1, *reference);
    if (!std::isfinite(x0)) x0 = 0, x1 = 1;
    const double pad = x1 > x0 ? 0.05 * (x1 - x0) : 1.0;
    x0 -= pad, x1 += pad;
  }
  const double height = kTop + kRow * static_cast<double>(rows.size()) + kBottom, plot = kWidth - kLeft - kRight;
  const auto x = [&](double v) { return kLeft + plot * (std::clamp(v, x0, x1) - x0) / (x1 - x0); };
  std::string svg = "<svg class=\"interval-plot " + css_class + "\" xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 " +
                    at(kWidth) + " " + at(height) + "\" width=\"" + at(kWidth) + "\" height=\"" + at(height) +
                    "\" role=\"img\" aria-label=\"" + html_escape(x_label) + " with 95% intervals\">";
  svg += "<rect class=\"frame\" x=\"" + at(kLeft) + "\" y=\"" + at(kTop) + "\" width=\"" + at(plot) + "\" height=\"" +
         at(kRow * static_cast<double>(rows.size())) + "\"/>";
  if (reference)
    svg += "<line class=\"reference\" x1=\"" + at(x(*reference)) + "\" y1=\"" + at(kTop) + "\" x2=\"" + at(x(*reference)) +
           "\" y2=\"" + at(kTop + kRow * static_cast<double>(rows.size())) + "\"/>";
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const IntervalRow& r = rows[i];
    const double y = kTop + kRow * (static_cast<double>(i) + 0.5);
    svg += text(kLeft - 6, y + 4, "end", html_escape(r.label));
    if (r.lo && r.hi && std::isfinite(*r.lo) && std::isfinite(*r.hi))
      svg += "<line class=\"interval\" x1=\"" + at(x(*r.lo)) + "\" y1=\"" + at(y) + "\" x2=\"" + at(x(*r.hi)) + "\" y2=\"" +
             at(y) + "\" stroke=\"" + html_escape(r.colour) + "\"/>";
    if (r.point && std::isfinite(*r.point))
      svg += "<circle class=\"point\" cx=\"" + at(x(*r.point)) + "\" cy=\"" + at(y) + "\" r=\"3.5\" fill=\"" +
             html_escape(r.colour) + "\"><title>" + html_escape(r.label) + ": " + short_number(r.point) + "</title></circle>";
  }
  const double axis = kTop + kRow * static_cast<double>(rows.size());
  svg += text(kLeft, axis + 14, "start", short_number(x0)) + text(kWidth - kRight, axis + 14, "end", short_number(x1));
  if (reference) svg += text(x(*reference), axis + 14, "middle", short_number(reference));
  svg += text(kLeft + plot / 2, axis + 28, "middle", html_escape(x_label));
  return svg + "</svg>";
}

std::string performance_profile_svg(const std::vector<ProfileSeries>& series, const std::string& title) {
  double x0 = INFINITY, x1 = -INFINITY;
  for (const ProfileSeries& s : series)
    for (double v : s.finals)
      if (std::isfinite(v)) x0 = std::min(x0, v), x1 = std::max(x1, v);
  if (!std::isfinite(x0)) return "";  // no run anywhere
  if (!(x1 > x0)) x0 -= 1, x1 += 1;
  constexpr double kWidth = 420, kHeight = 220, kLeft = 44, kRight = 110, kTop = 22, kBottom = 34;
  const double w = kWidth - kLeft - kRight, h = kHeight - kTop - kBottom;
  const auto x = [&](double v) { return kLeft + w * (v - x0) / (x1 - x0); };
  const auto y = [&](double share) { return kTop + h * (1.0 - share); };
  std::string svg = "<svg class=\"profile\" xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 " + at(kWidth) + " " +
                    at(kHeight) + "\" width=\"" + at(kWidth) + "\" height=\"" + at(kHeight) + "\" role=\"img\" aria-label=\"" +
                    html_escape(title) + "\">";
  svg += text(kLeft + w / 2, 14, "middle", html_escape(title), " class=\"title\"");
  svg += "<rect class=\"frame\" x=\"" + at(kLeft) + "\" y=\"" + at(kTop) + "\" width=\"" + at(w) + "\" height=\"" + at(h) + "\"/>";
  svg += text(kLeft - 4, kTop + 4, "end", "1") + text(kLeft - 4, kTop + h + 4, "end", "0");
  svg += text(kLeft, kTop + h + 14, "start", short_number(x0)) + text(kLeft + w, kTop + h + 14, "end", short_number(x1));
  svg += text(kLeft + w / 2, kTop + h + 28, "middle", "final return τ (share of runs above it)");
  int legend = 0;
  for (const ProfileSeries& s : series) {
    std::vector<double> v;
    for (double f : s.finals)
      if (std::isfinite(f)) v.push_back(f);
    if (v.empty()) continue;
    std::sort(v.begin(), v.end());
    const double n = static_cast<double>(v.size());
    std::string points = at(x(x0)) + "," + at(y(1.0));
    for (std::size_t i = 0; i < v.size(); ++i) {
      const double before = (n - static_cast<double>(i)) / n, after = (n - static_cast<double>(i) - 1) / n;
      points += " " + at(x(v[i])) + "," + at(y(before)) + " " + at(x(v[i])) + "," + at(y(after));
    }
    points += " " + at(x(x1)) + "," + at(y(0.0));
    svg += "<polyline points=\"" + points + "\" stroke=\"" + html_escape(s.colour) + "\"><title>" + html_escape(s.label) +
           " (" + std::to_string(v.size()) + " runs)</title></polyline>";
    svg += "<rect x=\"" + at(kLeft + w + 10) + "\" y=\"" + at(kTop + 4 + 14 * legend) + "\" width=\"10\" height=\"10\" fill=\"" +
           html_escape(s.colour) + "\"/>" + text(kLeft + w + 24, kTop + 13 + 14 * legend, "start", html_escape(s.label));
    ++legend;
  }
  return svg + "</svg>";
}

std::string seed_dots_svg(const std::vector<SeedDot>& dots, std::optional<double> mean, std::optional<double> std,
                          std::pair<double, double> range) {
  if (dots.empty()) return "";
  auto [x0, x1] = range;
  if (!(x1 > x0)) x0 -= 1, x1 += 1;
  constexpr double kWidth = 640, kLeft = 16, kRight = 16, kTop = 6, kRows = 3, kRowStep = 7, kHeight = 58;
  const double w = kWidth - kLeft - kRight, middle = kTop + kRowStep * kRows / 2;
  const auto x = [&](double v) { return kLeft + w * (std::clamp(v, x0, x1) - x0) / (x1 - x0); };
  std::string svg = "<svg class=\"seed-dots\" xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 " + at(kWidth) + " " +
                    at(kHeight) + "\" width=\"" + at(kWidth) + "\" height=\"" + at(kHeight) +
                    "\" role=\"img\" aria-label=\"every seed's final return beside the mean and std\">";
  const double axis = kTop + kRowStep * kRows + 8;
  svg += "<line class=\"axis\" x1=\"" + at(kLeft) + "\" y1=\"" + at(axis) + "\" x2=\"" + at(kLeft + w) + "\" y2=\"" + at(axis) + "\"/>";
  if (mean && std::isfinite(*mean)) {
    if (std && std::isfinite(*std))
      svg += "<line class=\"spread\" x1=\"" + at(x(*mean - *std)) + "\" y1=\"" + at(axis) + "\" x2=\"" +
             at(x(*mean + *std)) + "\" y2=\"" + at(axis) + "\"><title>mean ± std</title></line>";
    svg += "<line class=\"mean\" x1=\"" + at(x(*mean)) + "\" y1=\"" + at(kTop) + "\" x2=\"" + at(x(*mean)) + "\" y2=\"" +
           at(axis + 4) + "\"><title>mean " + short_number(mean) + "</title></line>";
  }
  // Three rows of dots, seed by seed, so that equal returns stay visible.
  for (std::size_t i = 0; i < dots.size(); ++i) {
    const double y = middle + kRowStep * (static_cast<double>(i % 3) - 1.0);
    svg += "<circle class=\"seed\" cx=\"" + at(x(dots[i].value)) + "\" cy=\"" + at(y) + "\" r=\"3\" fill=\"" +
           html_escape(dots[i].colour) + "\"><title>" + html_escape(dots[i].label) + ": " + short_number(dots[i].value) +
           "</title></circle>";
  }
  svg += text(kLeft, axis + 14, "start", short_number(x0)) + text(kLeft + w, axis + 14, "end", short_number(x1));
  return svg + "</svg>";
}

}  // namespace rapid
