#include "experiments/report/seed_curves_svg.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include "experiments/report/format.hpp"

namespace rapid {

namespace {

constexpr double kWidth = 420, kHeight = 200;
constexpr double kLeft = 56, kRight = 10, kTop = 10, kBottom = 30;

// Coordinates with one decimal: enough on screen, and the same text on every machine.
std::string coordinate(double x) { return fixed(x, 1); }

std::string text(double x, double y, const std::string& anchor, const std::string& content) {
  return "<text x=\"" + coordinate(x) + "\" y=\"" + coordinate(y) + "\" text-anchor=\"" + anchor + "\">" + content + "</text>";
}

}  // namespace

std::string seed_colour(std::size_t index) {
  // Ten colours that stay apart on white (the seed counts of the shipped grids are 1 to 10).
  static constexpr std::array<const char*, 10> kColours = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e",
                                                           "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};
  return kColours[index % kColours.size()];
}

std::string seed_curves_svg(const std::map<std::uint64_t, SeedCurve>& curves,
                            const std::map<std::uint64_t, std::string>& colours) {
  double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
  for (const auto& [seed, curve] : curves)
    for (const auto& [x, y] : curve) {
      x0 = std::min(x0, x), x1 = std::max(x1, x);
      y0 = std::min(y0, y), y1 = std::max(y1, y);
    }
  if (!std::isfinite(x0) || !std::isfinite(y0)) return "";
  // A flat curve or a single point still gets a visible range.
  if (x1 == x0) x1 = x0 + 1;
  if (y1 == y0) y0 -= 1, y1 += 1;
  const double plot_w = kWidth - kLeft - kRight, plot_h = kHeight - kTop - kBottom;
  const auto px = [&](double x) { return kLeft + (x - x0) / (x1 - x0) * plot_w; };
  const auto py = [&](double y) { return kTop + (y1 - y) / (y1 - y0) * plot_h; };

  std::string svg = "<svg class=\"seed-curves\" xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 " + coordinate(kWidth) +
                    " " + coordinate(kHeight) + "\" width=\"" + coordinate(kWidth) + "\" height=\"" + coordinate(kHeight) +
                    "\" role=\"img\" aria-label=\"evaluation return of every seed against env steps\">";
  svg += "<rect class=\"frame\" x=\"" + coordinate(kLeft) + "\" y=\"" + coordinate(kTop) + "\" width=\"" +
         coordinate(plot_w) + "\" height=\"" + coordinate(plot_h) + "\"/>";
  svg += text(kLeft - 4, kTop + 10, "end", short_number(y1)) + text(kLeft - 4, kTop + plot_h, "end", short_number(y0));
  // Steps are whole numbers: written out in full ("10000"), not as "1e+04".
  svg += text(kLeft, kHeight - 14, "start", fixed(x0, 0)) + text(kLeft + plot_w, kHeight - 14, "end", fixed(x1, 0));
  svg += text(kLeft + plot_w / 2, kHeight - 2, "middle", "env steps");
  for (const auto& [seed, curve] : curves) {
    const auto colour_of = colours.find(seed);
    const std::string colour = colour_of == colours.end() ? "black" : colour_of->second;
    std::string points;
    for (const auto& [x, y] : curve) points += (points.empty() ? "" : " ") + coordinate(px(x)) + "," + coordinate(py(y));
    svg += "<polyline data-seed=\"" + std::to_string(seed) + "\" stroke=\"" + colour + "\" points=\"" + points +
           "\"><title>seed " + std::to_string(seed) + "</title></polyline>";
  }
  return svg + "</svg>";
}

}  // namespace rapid
