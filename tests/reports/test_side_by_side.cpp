// `rapid beside NOW BEFORE` (report/side_by_side.hpp): two reports of the same rows side by side.
// What a reader relies on: every cell shows its own mean ± std and the other report's mean of the
// same cell; a report beside itself changes nothing; a verdict or an outcome that differs is
// listed, and only those; bad input is one line and exit 2.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "experiments/report/format.hpp"
#include "experiments/report/side_by_side.hpp"
#include "tests/cli_runner.hpp"
#include "tests/datasets/dataset_fixtures.hpp"
#include "tests/reports/report_test_util.hpp"

namespace rapid {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::rapid_cli;

const fs::path kRerun = fs::path(RAPID_SOURCE_DIR) / "results" / "extension-flow";
const fs::path kHandicapped = kRerun / "handicapped";

json summary_of(const fs::path& dir) { return json::parse(report_test::read_text(dir / "summary.json")); }

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

std::size_t cell_index(const json& summary, const std::string& scenario, const std::string& dataset, const std::string& algo) {
  for (std::size_t i = 0; i < summary["cells"].size(); ++i) {
    const json& c = summary["cells"][i];
    if (c["scenario"] == scenario && c["dataset"] == dataset && c["algo"] == algo) return i;
  }
  throw std::runtime_error("no cell " + scenario + "/" + dataset + "/" + algo);
}

// Beside itself: every cell's bracket is its own mean, no verdict and no outcome changed.
TEST(SideBySide, AReportBesideItselfChangesNothing) {
  const json s = summary_of(kRerun);
  const std::string md = side_by_side_markdown(s, "a", s, "b");
  EXPECT_TRUE(has(md, "0 verdicts changed")) << md;
  const std::size_t n = s["baseline_decisions"]["comparisons"].size();
  EXPECT_TRUE(has(md, std::to_string(n) + " of " + std::to_string(n) + " comparisons have the same outcome in both.")) << md;
  for (const json& c : s["cells"]) {
    if (c["dataset"].is_null()) continue;  // DDPG's cell repeats in its scenario's rows
    const std::string mean = fixed(c["mean"].get<double>(), 1);
    EXPECT_TRUE(has(md, mean + " ± " + fixed(c["std"].get<double>(), 1) + " (" + mean + ")")) << c["scenario"] << c["algo"];
  }
}

// A planted change in the earlier report is shown where it was planted and nowhere else: one cell's
// mean, one claim's verdict, one comparison's outcome.
TEST(SideBySide, ShowsEachPlantedChangeAndOnlyThose) {
  const json now = summary_of(kRerun);
  json before = now;
  const std::size_t planted_cell = cell_index(now, "merge", "medium", "rlpd-sac");
  before["cells"][planted_cell]["mean"] = 123.4;
  before["decisions"]["claims"][2]["verdict"] = "CONFIRMED";
  json& comparison = before["baseline_decisions"]["comparisons"][4];
  comparison["outcome"] = comparison["outcome"] == "undecided" ? "y better" : "undecided";
  const std::string md = side_by_side_markdown(now, "now", before, "before");

  const json& cell = now["cells"][planted_cell];
  EXPECT_TRUE(has(md, fixed(cell["mean"].get<double>(), 1) + " ± " + fixed(cell["std"].get<double>(), 1) + " (123.4)")) << md;
  const std::string claim = now["decisions"]["claims"][2]["id"].get<std::string>();
  EXPECT_TRUE(has(md, "| " + claim + " | **" + now["decisions"]["claims"][2]["verdict"].get<std::string>() + "** | CONFIRMED |"))
      << md;
  EXPECT_TRUE(has(md, "1 verdict changed")) << md;
  const std::size_t n = now["baseline_decisions"]["comparisons"].size();
  EXPECT_TRUE(has(md, std::to_string(n - 1) + " of " + std::to_string(n) + " comparisons have the same outcome")) << md;
  const json& planted = now["baseline_decisions"]["comparisons"][4];
  EXPECT_TRUE(has(md, "| " + planted["where"].get<std::string>() + " | " + planted["x"].get<std::string>() + " vs " +
                          planted["y"].get<std::string>() + " | "))
      << md;
}

// The committed pair (issue #41's rerun beside its handicapped first run): the Q-filter was not in
// the first run, the paper's five are the same runs, and TD3+BC's new decided rows are listed.
TEST(SideBySide, TheRerunBesideTheHandicappedRun) {
  const std::string md = side_by_side_markdown(summary_of(kRerun), "rerun", summary_of(kHandicapped), "handicapped");
  EXPECT_TRUE(has(md, "| Lane-drop | Initial | 449.9 ± 75.7 (449.9) |")) << md;
  EXPECT_TRUE(has(md, "644.0 ± 77.8 (613.7)")) << md;
  EXPECT_TRUE(has(md, "419.7 ± 89.1 (—)")) << md;
  EXPECT_TRUE(has(md, "| RLPD (SAC) | 595.7 [569.0, 620.3] | 564.3 [535.7, 591.0] |")) << md;
  EXPECT_TRUE(has(md, "| lane-drop / final+medium | RAPID-RL vs TD3+BC | RAPID-RL higher | undecided |")) << md;
  EXPECT_TRUE(has(md, "| merge / medium | RAPID-RL vs Q-filter | undecided | not compared |")) << md;
  EXPECT_FALSE(has(md, "| merge / medium | RAPID-RL vs TD3+BC |")) << "decided in both, not a change";
  EXPECT_THROW(side_by_side_markdown(summary_of(kRerun), "a", json{{"cells", json::array()}, {"table", json::array()},
                                                                   {"algorithms", json::array()}},
                                     "b"),
               std::invalid_argument);
}

TEST(SideBySideCli, PrintsOrWritesAndRefusesBadInputWithOneLine) {
  testing::ScratchDir scratch;
  const std::string pair = kRerun.string() + " " + kHandicapped.string();
  const test::CliOutput out = rapid_cli("beside " + pair + " --labels rerun,handicapped");
  ASSERT_EQ(out.exit_code, 0) << out.text;
  EXPECT_EQ(out.text, side_by_side_markdown(summary_of(kRerun), "rerun", summary_of(kHandicapped), "handicapped"));
  EXPECT_TRUE(has(rapid_cli("beside " + pair).text, "# extension-flow beside handicapped")) << "default labels: folder names";

  const fs::path file = scratch.path() / "beside.md";
  ASSERT_EQ(rapid_cli("beside " + pair + " --labels rerun,handicapped --out " + file.string()).exit_code, 0);
  EXPECT_EQ(report_test::read_text(file), out.text);

  const auto one_line_exit_2 = [](const test::CliOutput& r, const std::string& names) {
    EXPECT_EQ(r.exit_code, 2) << r.text;
    EXPECT_EQ(std::count(r.text.begin(), r.text.end(), '\n'), 1) << r.text;
    EXPECT_TRUE(has(r.text, names)) << r.text;
  };
  one_line_exit_2(rapid_cli("beside " + scratch.path().string() + " " + kRerun.string(), true), "NOW: ");
  one_line_exit_2(rapid_cli("beside " + kRerun.string() + " " + scratch.path().string(), true), "BEFORE: ");
  one_line_exit_2(rapid_cli("beside " + pair + " --labels onlyone", true), "--labels: ");

  // Issue #67: a label is text, never markup, whether given or a folder's name.
  const std::string marked = rapid_cli("beside " + pair + " --labels '<script>x()</script>|x,b'").text;
  EXPECT_TRUE(has(marked, "# \\<script\\>x()\\</script\\> x beside b")) << marked;
  EXPECT_FALSE(has(marked, "<script>")) << marked;
  const fs::path odd = scratch.path() / "<img src=x>";
  fs::create_directories(odd);
  fs::copy_file(kHandicapped / "summary.json", odd / "summary.json");
  const std::string by_folder = rapid_cli("beside " + kRerun.string() + " '" + odd.string() + "'").text;
  EXPECT_TRUE(has(by_folder, "beside \\<img src=x\\>")) << by_folder;
  EXPECT_FALSE(has(by_folder, "<img src=x>")) << by_folder;
  one_line_exit_2(rapid_cli("beside " + pair + " --out " + (scratch.path() / "missing" / "x.md").string(), true), "--out: ");
  one_line_exit_2(rapid_cli("beside " + pair + " --out " + scratch.path().string(), true), "--out: ");

  // A summary whose rows are all another scenario's: nothing to set beside.
  const fs::path other = scratch.path() / "other";
  fs::create_directories(other);
  json s = summary_of(kRerun);
  for (json& row : s["table"]) row["scenario"] = "pendulum";
  std::ofstream(other / "summary.json") << s.dump();
  one_line_exit_2(rapid_cli("beside " + other.string() + " " + kRerun.string(), true), "no Table I row in common");

  // A cell without its algorithm would key no column and vanish from the table: refused, by index.
  const fs::path broken = scratch.path() / "broken";
  fs::create_directories(broken);
  json b = summary_of(kRerun);
  b["cells"][3].erase("algo");
  std::ofstream(broken / "summary.json") << b.dump();
  one_line_exit_2(rapid_cli("beside " + broken.string() + " " + kRerun.string(), true), "NOW: ");
  one_line_exit_2(rapid_cli("beside " + kRerun.string() + " " + broken.string(), true), "cells[3] has no string \"algo\"");
  b = summary_of(kRerun);
  b["cells"][0]["dataset"] = 7;
  std::ofstream(broken / "summary.json") << b.dump();
  one_line_exit_2(rapid_cli("beside " + broken.string() + " " + kRerun.string(), true), "cells[0] has no \"dataset\"");
}

}  // namespace
}  // namespace rapid
