// report.html (experiments/report/report_page.hpp) as `rapid summarize` writes it: on hand-made
// sweeps with failed and missing seeds and a variant algorithm, on the committed results folders
// (grids with axes, no records) through --html-only, byte for byte, and on bad input. The page in
// a real browser: tests/browser (scripts/test-browser).
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <regex>
#include <set>
#include <vector>

#include "experiments/report/report_folder.hpp"
#include "experiments/report/report_page.hpp"
#include "tests/cli_runner.hpp"
#include "tests/datasets/dataset_fixtures.hpp"
#include "tests/reports/report_test_util.hpp"

namespace rapid {
namespace {

namespace fs = std::filesystem;
using test::rapid_cli;

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

class ReportPageTest : public ::testing::Test {
 protected:
  testing::ScratchDir scratch;
  fs::path sweep = scratch.path() / "sweep";

  // One scenario, RAPID-RL and its variant with two datasets, DDPG; seed 2 of rapid-rl/initial
  // failed, seed 1 of ddpg never ran.
  void SetUp() override {
    nlohmann::json grid = report_test::make_grid("page", {"pendulum"}, {"initial", "final+medium"},
                                                 {"rapid-rl", "rapid-rl-return", "ddpg"}, {0, 1, 2});
    grid["config"]["return_horizon"] = 20;
    report_test::write_grid(sweep, grid);
    for (const std::string dataset : {"initial", "final+medium"})
      for (const std::string algo : {"rapid-rl", "rapid-rl-return"})
        for (std::uint64_t seed : {0u, 1u, 2u}) {
          const bool failed = dataset == "initial" && algo == "rapid-rl" && seed == 2;
          report_test::write_run(sweep, report_test::pendulum_run(dataset, algo, seed, 100.0 + 10 * seed,
                                                                  failed ? "failed" : "ok"));
        }
    for (std::uint64_t seed : {0u, 2u}) report_test::write_run(sweep, report_test::pendulum_run("", "ddpg", seed, 50.0 + seed));
  }
  std::string summarize_page() {
    const auto out = rapid_cli("summarize " + sweep.string() + " --no-plots", true);
    EXPECT_EQ(out.exit_code, 0) << out.text;
    EXPECT_TRUE(has(out.text, "report.html")) << out.text;
    return report_test::read_text(sweep / "report.html");
  }
};

TEST_F(ReportPageTest, ShowsEverySeedWithItsStatusAndItsRecord) {
  const std::string page = summarize_page();
  // Table I as table.md writes it, the short cells with their counts, the variant as a column.
  EXPECT_TRUE(has(page, ">105.0 ± 5.0 (n=2/3)</a>")) << "rapid-rl/initial without its failed seed";
  EXPECT_TRUE(has(page, ">51.0 ± 1.0 (n=2/3)</a>")) << "ddpg without its missing seed";
  EXPECT_TRUE(has(page, "<th scope=\"col\">RAPID-RL (return)</th>"));
  EXPECT_TRUE(has(page, "RAPID-RL (return) &gt; RAPID-RL")) << "the variant's probability of improvement";
  // The drill-down: statuses, errors, links relative to the page, the curve of every ok seed.
  EXPECT_TRUE(has(page, "status-failed\">failed</td>"));
  EXPECT_TRUE(has(page, "training failed"));
  EXPECT_TRUE(has(page, "status-missing\">missing</td>"));
  EXPECT_TRUE(has(page, "<a href=\"jobs/pendulum/initial/rapid-rl/seed0/record.json\">record.json</a>"));
  EXPECT_TRUE(has(page, "<code class=\"absent\" title=\"not in this folder\">jobs/pendulum/none/ddpg/seed1/record.json</code>"));
  EXPECT_TRUE(has(page, "<polyline data-seed=\"1\"")) << "seed curves from runs.csv";
  EXPECT_TRUE(has(page, "figure2: not drawn")) << "--no-plots: the page says the figures are missing";
  // Nothing that changes between runs or machines, nothing fetched.
  EXPECT_FALSE(has(page, scratch.path().string()));
  EXPECT_FALSE(has(page, "https://"));
  EXPECT_FALSE(has(page, "<link"));
  const nlohmann::json summary = report_test::read_json(sweep / "summary.json");
  EXPECT_EQ(summary["provenance"]["runs"], 13) << summary["provenance"];
}

TEST_F(ReportPageTest, RegeneratesByteForByteAndFromTheFolderAlone) {
  const std::string first = summarize_page();
  EXPECT_EQ(summarize_page(), first);
  const auto out = rapid_cli("summarize " + sweep.string() + " --html-only", true);
  ASSERT_EQ(out.exit_code, 0) << out.text;
  EXPECT_EQ(report_test::read_text(sweep / "report.html"), first);
}

TEST_F(ReportPageTest, AReportsFolderElsewhereLinksBackToTheRecords) {
  const auto out = rapid_cli("summarize " + sweep.string() + " --no-plots --out " + (scratch.path() / "reports").string(), true);
  ASSERT_EQ(out.exit_code, 0) << out.text;
  const std::string page = report_test::read_text(scratch.path() / "reports" / "report.html");
  EXPECT_TRUE(has(page, "<a href=\"../sweep/jobs/pendulum/initial/rapid-rl/seed0/record.json\">record.json</a>"));
}

TEST_F(ReportPageTest, BadInputExitsTwoWithOneLineAndWritesNothing) {
  const fs::path empty = scratch.path() / "empty";
  fs::create_directories(empty);
  auto out = rapid_cli("summarize " + empty.string() + " --html-only", true);
  EXPECT_EQ(out.exit_code, 2) << out.text;
  EXPECT_TRUE(has(out.text, "summary.json")) << out.text;
  EXPECT_EQ(std::count(out.text.begin(), out.text.end(), '\n'), 1) << out.text;
  EXPECT_FALSE(fs::exists(empty / "report.html"));

  report_test::write_text(empty / "summary.json", "{\"schema\": \"rapid.baseline/1\"}");
  out = rapid_cli("summarize " + empty.string() + " --html-only", true);
  EXPECT_EQ(out.exit_code, 2) << out.text;
  EXPECT_TRUE(has(out.text, "not a rapid.summary/1 document")) << out.text;
  EXPECT_FALSE(fs::exists(empty / "report.html"));

  out = rapid_cli("summarize " + sweep.string() + " --html-only --out " + empty.string(), true);
  EXPECT_EQ(out.exit_code, 2) << out.text;
  EXPECT_EQ(std::count(out.text.begin(), out.text.end(), '\n'), 1) << out.text;
}

// Every committed folder with a report.html (grids with and without axes, none with its records):
// its page is what --html-only makes of it now.
TEST(CommittedReportPages, RegenerateByteForByteFromTheCommittedFiles) {
  testing::ScratchDir scratch;
  const fs::path results = fs::path(RAPID_SOURCE_DIR) / "results";
  std::vector<std::string> folders;
  // A committed report folder holds no run records. A folder with a jobs/ folder is a sweep run
  // here (the README's main job writes results/quick-flow, the fresh-machine check
  // results/smoke), whose page links records git does not keep: not a committed page.
  for (const auto& entry : fs::recursive_directory_iterator(results))
    if (entry.path().filename() == "report.html" && !fs::exists(entry.path().parent_path() / "jobs"))
      folders.push_back(fs::relative(entry.path().parent_path(), results).string());
  std::sort(folders.begin(), folders.end());
  for (const std::string expected : {"quick", "paper-flow", "paper-flow-recheck", "ablations/recheck"})
    EXPECT_NE(std::find(folders.begin(), folders.end(), expected), folders.end()) << expected;
  for (const std::string& folder : folders) {
    const fs::path committed = results / folder;
    // Each into a folder of its own: a report folder may hold an older one (extension-flow/handicapped),
    // which a nested copy would meet twice. The copy keeps the folder's name, which titles its page.
    std::string flat = folder;
    std::replace(flat.begin(), flat.end(), '/', '_');
    const fs::path copy = scratch.path() / flat / committed.filename();
    fs::create_directories(copy.parent_path());
    fs::copy(committed, copy, fs::copy_options::recursive);
    fs::remove(copy / "report.html");
    const auto out = rapid_cli("summarize " + copy.string() + " --html-only", true);
    ASSERT_EQ(out.exit_code, 0) << folder << "\n" << out.text;
    const std::string page = report_test::read_text(copy / "report.html");
    EXPECT_EQ(page, report_test::read_text(committed / "report.html"))
        << folder << ": the committed report.html is out of date; rapid summarize results/" << folder << " --html-only";
    if (folder == "ablations/recheck") {
      EXPECT_TRUE(has(page, "<th scope=\"col\">Axes</th>"));
      EXPECT_TRUE(has(page, "alt=\"sensitivity-epsilon\""));
      EXPECT_TRUE(has(page, "alt=\"sensitivity-return_horizon\""));
    }
    EXPECT_TRUE(has(page, "The run records are not in this folder")) << folder;
  }
}

// Every value of summary.json, grid.json and sweep.json that reaches the page is escaped (issue 46:
// `summarize --html-only` once put grid.seeds, status counts and provenance counts into the page
// raw, and Chromium ran the handler). For each field of two committed folders (one with adaptive
// seeds, one with the published baselines), one at a time, in each kind of place the field takes
// (array indices folded, so /cells/0/seeds/3/final stands for every seed's final): the field
// becomes a hostile string, and the page either is refused (a wrong type is bad input, exit 2 by
// write_report_page) or shows it as text: no tag or handler of it survives.
TEST(ReportPageInput, AHostileStringInAnyFieldIsShownAsTextNeverRun) {
  const std::string hostile = "<img src=x onerror=alert(1)>\"'</script><script>alert(2)</script>";
  int fields = 0, refused = 0;
  for (const char* name : {"paper-flow-decided", "extension-flow"}) {
    ReportFolder folder = read_report_folder(fs::path(RAPID_SOURCE_DIR) / "results" / name,
                                             fs::path(RAPID_SOURCE_DIR) / "results" / name);
    const auto attack = [&](nlohmann::json& doc, const std::string& file) {
      const nlohmann::json flat = doc.flatten();
      std::set<std::string> seen;
      for (const auto& [pointer, value] : flat.items()) {
        const std::string kind = std::regex_replace(pointer, std::regex("/[0-9]+(/|$)"), "/#$1");
        if (!seen.insert(kind).second) continue;
        const nlohmann::json::json_pointer where(pointer);
        const nlohmann::json original = doc[where];
        doc[where] = hostile;
        ++fields;
        try {
          const std::string page = report_page_html(folder);
          EXPECT_EQ(page.find("<img src=x"), std::string::npos) << name << " " << file << pointer;
          EXPECT_EQ(page.find("<script>alert"), std::string::npos) << name << " " << file << pointer;
        } catch (const nlohmann::json::exception&) {
          ++refused;
        }
        doc[where] = original;
      }
    };
    attack(folder.summary, "summary.json");
    attack(folder.grid_document, "grid.json");
    if (folder.manifest) attack(*folder.manifest, "sweep.json");
  }
  EXPECT_GT(fields, 300);
  std::cout << fields << " kinds of field made hostile; " << refused << " refused as the wrong type, the rest shown as text\n";
}

// The page answers first: before the provenance, each decided claim with its verdict, its reason
// and, where undecided, how many comparisons are open and the fewest seeds one of them needs; the
// highest mean per row; RAPID-RL against the baselines the paper does not run. A summary without
// decisions says its PASS/FAIL are point means, not decisions.
TEST(ReportPageAnswer, TheVerdictsComeFirstWithWhatWouldDecideThem) {
  ReportFolder folder = read_report_folder(fs::path(RAPID_SOURCE_DIR) / "results" / "extension-flow",
                                           fs::path(RAPID_SOURCE_DIR) / "results" / "extension-flow");
  std::string page = report_page_html(folder);
  const std::size_t answer = page.find("<section id=\"answer\">"), provenance = page.find("<section id=\"provenance\">");
  ASSERT_NE(answer, std::string::npos);
  ASSERT_LT(answer, provenance);
  std::string section = page.substr(answer, provenance - answer);
  const nlohmann::json& d = folder.summary["decisions"];
  for (const nlohmann::json& claim : d["claims"]) {
    EXPECT_TRUE(has(section, "<td>" + claim["id"].get<std::string>() + "</td>")) << claim["id"];
    EXPECT_TRUE(has(section, claim["reason"].get<std::string>())) << claim["id"];
    if (claim["verdict"] != "UNDECIDED") continue;
    int open = 0;
    long nearest = 1L << 40;
    for (const nlohmann::json& i : claim["comparisons"]) {
      const nlohmann::json& c = d["comparisons"][i.get<std::size_t>()];
      if (c["outcome"] != "undecided") continue;
      ++open;
      nearest = std::min(nearest, c["seeds_needed"].get<long>());
    }
    EXPECT_TRUE(has(section, std::to_string(open) + " comparison" + (open == 1 ? "" : "s") + " undecided; the nearest needs about " +
                                 std::to_string(nearest) + " seeds"))
        << claim["id"];
  }
  for (const nlohmann::json& row : folder.summary["table"])
    for (const nlohmann::json& a : folder.summary["algorithms"])
      if (a["name"] == row["best"]) EXPECT_TRUE(has(section, "<b>" + a["label"].get<std::string>() + "</b>"));
  EXPECT_TRUE(has(section, "against RLPD (SAC), ")) << section;

  folder.summary.erase("decisions");
  page = report_page_html(folder);
  section = page.substr(page.find("<section id=\"answer\">"));
  EXPECT_TRUE(has(section.substr(0, section.find("</section>")), "so PASS and FAIL here are not decisions"));
}

// Issue #67: the decided folder's page was titled "Sweep paper-flow" (its grid's name) and said
// "15 missing" and "765 … built with uncommitted changes" without a word more. A page is named
// after its folder, with the grid beside it when that differs, and both lines say what they mean.
TEST(ReportPageTitle, NamesItsFolderAndExplainsMissingAndUncommitted) {
  const fs::path decided = fs::path(RAPID_SOURCE_DIR) / "results" / "paper-flow-decided";
  const std::string page = report_page_html(read_report_folder(decided, decided));
  EXPECT_TRUE(has(page, "<title>RAPID-RL reports paper-flow-decided</title>"));
  EXPECT_TRUE(has(page, "<h1>Reports <code>paper-flow-decided</code> (grid <code>paper-flow</code>)</h1>"));
  EXPECT_TRUE(has(page, "15 missing, 1155 ok in 39 cells. Missing: seeds of the grid this adaptive sweep did not run"));
  EXPECT_TRUE(has(page, "765 of them built with uncommitted changes (the working tree differed from the revision"));
  const fs::path plain = fs::path(RAPID_SOURCE_DIR) / "results" / "paper-flow";
  const std::string same = report_page_html(read_report_folder(plain / "", plain / ""));
  EXPECT_TRUE(has(same, "<h1>Reports <code>paper-flow</code></h1>"));
}

// A field of the wrong type is bad input: one line naming the file, exit 2, no page.
TEST(ReportPageInput, AWrongTypedFieldIsBadInput) {
  testing::ScratchDir scratch;
  const fs::path copy = scratch.path() / "x";
  fs::copy(fs::path(RAPID_SOURCE_DIR) / "results" / "slow-start-merge", copy, fs::copy_options::recursive);
  fs::remove(copy / "report.html");
  nlohmann::json summary = nlohmann::json::parse(report_test::read_text(copy / "summary.json"));
  summary["provenance"]["dirty_runs"] = "many";
  std::ofstream(copy / "summary.json") << summary.dump();
  const auto out = rapid_cli("summarize " + copy.string() + " --html-only", true);
  EXPECT_EQ(out.exit_code, 2) << out.text;
  EXPECT_EQ(std::count(out.text.begin(), out.text.end(), '\n'), 1) << out.text;
  EXPECT_TRUE(has(out.text, "summary.json")) << out.text;
  EXPECT_FALSE(fs::exists(copy / "report.html"));
}

}  // namespace
}  // namespace rapid
