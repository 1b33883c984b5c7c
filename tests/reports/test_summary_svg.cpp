// rliable's figures as SVG: a point per row that has one (and its interval line), a label for
// every row, the reference line where asked; a performance profile's step line falls from every
// run above τ to none, one step per run, at the runs' own returns.
#include <gtest/gtest.h>

#include <regex>

#include "experiments/report/summary_svg.hpp"

namespace rapid {
namespace {

std::size_t count(const std::string& text, const std::string& part) {
  std::size_t n = 0;
  for (std::size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

TEST(SummarySvg, AnIntervalPlotDrawsAPointPerRowThatHasOne) {
  const std::string svg = interval_plot_svg({{"a > b", 0.7, 0.6, 0.8, "#d62728"}, {"a > <c>", std::nullopt, std::nullopt, std::nullopt, "#1f77b4"}},
                                            "poi-plot", "P(X > Y)", 0.5, std::pair{0.0, 1.0});
  EXPECT_EQ(count(svg, "<circle class=\"point\""), 1u);
  EXPECT_EQ(count(svg, "<line class=\"interval\""), 1u);
  EXPECT_EQ(count(svg, "<line class=\"reference\""), 1u);
  EXPECT_NE(svg.find("a &gt; &lt;c&gt;"), std::string::npos) << "labels are text";
  // The point at 0.7 of the [0, 1] axis: 250 + 0.7 · 374 (the plot's left and width).
  EXPECT_NE(svg.find("cx=\"511.8\""), std::string::npos) << svg;
  EXPECT_TRUE(interval_plot_svg({}, "x", "y").empty());
}

TEST(SummarySvg, AProfileStepsDownOnceAtEachRun) {
  const std::string svg = performance_profile_svg({{"A", "#d62728", {4.0, 1.0, 3.0, 2.0}}, {"none", "#000", {}}}, "Merge");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(svg, m, std::regex("<polyline points=\"([^\"]*)\"")));
  std::vector<std::pair<double, double>> points;
  const std::string list = m[1];
  const std::regex pair("([-0-9.]+),([-0-9.]+)");
  for (auto it = std::sregex_iterator(list.begin(), list.end(), pair); it != std::sregex_iterator(); ++it)
    points.emplace_back(std::stod((*it)[1]), std::stod((*it)[2]));
  ASSERT_EQ(points.size(), 2u + 2u * 4u);  // the start, two corners per run, the end
  const double top = points.front().second, bottom = points.back().second;
  EXPECT_LT(top, bottom);  // y grows downwards: share 1 at the top
  for (std::size_t i = 1; i + 1 < points.size(); i += 2) {
    const double share_before = (bottom - points[i].second) / (bottom - top);
    const double share_after = (bottom - points[i + 1].second) / (bottom - top);
    EXPECT_NEAR(share_before - share_after, 0.25, 0.01) << i;  // each of the 4 runs a quarter
    EXPECT_EQ(points[i].first, points[i + 1].first);  // a vertical step at the run's return
  }
  EXPECT_EQ(count(svg, "<polyline"), 1u) << "a series without runs is left out";
  EXPECT_TRUE(performance_profile_svg({{"none", "#000", {}}}, "x").empty());
}

TEST(SummarySvg, SeedDotsDrawOneDotPerSeedOnTheGivenRange) {
  const std::string svg = seed_dots_svg({{"seed 0", 10.0, "#111"}, {"seed 1", 30.0, "#222"}, {"seed <2>", 30.0, "#333"}},
                                        std::optional<double>(70.0 / 3.0), std::optional<double>(9.43), {0.0, 40.0});
  EXPECT_EQ(count(svg, "<circle class=\"seed\""), 3u);
  EXPECT_EQ(count(svg, "<line class=\"spread\""), 1u);
  EXPECT_EQ(count(svg, "<line class=\"mean\""), 1u);
  EXPECT_NE(svg.find("seed &lt;2&gt;"), std::string::npos) << "labels are text";
  // 10 on [0, 40]: 16 + 0.25 · 608 (the strip's left and width).
  EXPECT_NE(svg.find("cx=\"168.0\""), std::string::npos) << svg;
  // Equal returns of neighbouring seeds sit on different rows, so both stay visible.
  EXPECT_NE(svg.find("cx=\"472.0\" cy=\"16.5\""), std::string::npos) << svg;
  EXPECT_NE(svg.find("cx=\"472.0\" cy=\"23.5\""), std::string::npos) << svg;
  EXPECT_TRUE(seed_dots_svg({}, std::nullopt, std::nullopt, {0.0, 1.0}).empty());
}

}  // namespace
}  // namespace rapid
