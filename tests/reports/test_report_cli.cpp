// `rapid summarize` and `rapid diff` as users run them: the built binary on hand-made sweeps.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>

#include <sys/wait.h>

#include "tests/cli_runner.hpp"
#include "tests/datasets/dataset_fixtures.hpp"
#include "tests/reports/report_test_util.hpp"
#include "tests/special_files.hpp"

namespace rapid {
namespace {

using report_test::FakeRun;
using test::rapid_cli;

class ReportCliTest : public ::testing::Test {
 protected:
  testing::ScratchDir scratch;
  std::filesystem::path sweep = scratch.path() / "sweep";
  std::filesystem::path baseline = scratch.path() / "baseline.json";

  void SetUp() override {
    report_test::write_grid(sweep, report_test::make_grid("cli", {"pendulum"}, {"initial", "final+medium"},
                                                          {"rapid-rl", "col-all", "ddpg"}, {0, 1, 2}));
    for (const std::string dataset : {"initial", "final+medium"})
      for (const std::string algo : {"rapid-rl", "col-all"})
        for (std::uint64_t seed : {0u, 1u, 2u}) run(dataset, algo, seed, 100.0 + 10 * seed + (algo == "col-all" ? -80 : 0));
    for (std::uint64_t seed : {0u, 1u, 2u}) run("", "ddpg", seed, 50.0 + seed);
  }
  void run(const std::string& dataset, const std::string& algo, std::uint64_t seed, double final,
           const std::string& status = "ok") {
    FakeRun r = report_test::pendulum_run(dataset, algo, seed, final, status);
    r.bc = {{0, 0.1, 0.5}, {500, 0.2, 0.4}};
    report_test::write_run(sweep, r);
  }
  test::CliOutput write_baseline() {
    return rapid_cli("diff " + sweep.string() + " " + baseline.string() + " --write-baseline", true);
  }
  test::CliOutput diff(const std::string& extra = "") {
    return rapid_cli("diff " + sweep.string() + " " + baseline.string() + extra, true);
  }
};

TEST_F(ReportCliTest, SummarizeWritesEveryReportAndShowsFailedSeeds) {
  run("initial", "rapid-rl", 2, 0, "failed");
  const auto out = rapid_cli("summarize " + sweep.string() + " --no-plots", true);
  ASSERT_EQ(out.exit_code, 0) << out.text;
  for (const char* f : {"table.md", "table.tex", "table.csv", "summary.json", "claims.md"})
    EXPECT_TRUE(std::filesystem::is_regular_file(sweep / f)) << f;
  const std::string md = report_test::read_text(sweep / "table.md");
  EXPECT_NE(md.find("105.0 ± 5.0 (n=2/3)"), std::string::npos) << md;
  EXPECT_EQ(report_test::read_json(sweep / "summary.json")["schema"], "rapid.summary/1");
  EXPECT_NE(out.text.find("C1 "), std::string::npos) << out.text;
  const std::string claims = report_test::read_text(sweep / "claims.md");
  EXPECT_NE(claims.find("## C3: "), std::string::npos) << claims;
  EXPECT_NE(claims.find("Point-mean check (not a decision): PASS. PASS when CoL-all's mean"), std::string::npos) << claims;
  // finals.csv: each run's final return, the number Table I averages, where a reader looks (#68).
  const std::string finals = report_test::read_text(sweep / "finals.csv");
  EXPECT_EQ(finals.rfind("scenario,dataset,algo,seed,status,final_return,final_episodes\n", 0), 0u) << finals;
  EXPECT_NE(finals.find("\npendulum,initial,rapid-rl,1,ok,110,"), std::string::npos) << finals;
  EXPECT_NE(finals.find("\npendulum,initial,rapid-rl,2,failed,,\n"), std::string::npos) << finals;
  EXPECT_NE(finals.find("\npendulum,none,ddpg,0,ok,50,"), std::string::npos) << finals;
  EXPECT_EQ(std::count(finals.begin(), finals.end(), '\n'), 1 + 15);  // 5 cells × 3 seeds
}

// A report file that is a symlink (or FIFO, device, folder) is refused before any report is
// rewritten: one line naming it, exit 2, the other reports as they were (issue 46 item 14).
TEST_F(ReportCliTest, AReportFileInTheWayStopsSummarizeBeforeAnythingIsWritten) {
  ASSERT_EQ(rapid_cli("summarize " + sweep.string() + " --no-plots", true).exit_code, 0);
  report_test::write_text(sweep / "table.md", "the table as it was\n");
  const std::filesystem::path elsewhere = scratch.path() / "elsewhere.md";
  report_test::write_text(elsewhere, "not a report\n");
  std::filesystem::remove(sweep / "claims.md");
  std::filesystem::create_symlink(elsewhere, sweep / "claims.md");
  const auto out = rapid_cli("summarize " + sweep.string() + " --no-plots", true);
  EXPECT_EQ(out.exit_code, 2) << out.text;
  EXPECT_NE(out.text.find("claims.md is a symlink, not a regular file; no report was written"), std::string::npos)
      << out.text;
  EXPECT_EQ(report_test::read_text(sweep / "table.md"), "the table as it was\n");
  EXPECT_EQ(report_test::read_text(elsewhere), "not a report\n");
}

TEST_F(ReportCliTest, SummarizeSaysSoWhenPythonHasNoMatplotlib) {
  ::setenv("RAPID_PYTHON", "/nonexistent/python3", 1);
  const auto out = rapid_cli("summarize " + sweep.string(), true);
  ::unsetenv("RAPID_PYTHON");
  EXPECT_EQ(out.exit_code, 0) << out.text;
  EXPECT_NE(out.text.find("figures skipped: /nonexistent/python3 has no matplotlib"), std::string::npos) << out.text;
  EXPECT_TRUE(std::filesystem::is_regular_file(sweep / "table.md"));
}

TEST_F(ReportCliTest, SummarizeDrawsTheFiguresWhenMatplotlibIsThere) {
  if (std::system("/usr/bin/python3 -c 'import matplotlib' >/dev/null 2>&1") != 0) GTEST_SKIP() << "no matplotlib";
  const auto out = rapid_cli("summarize " + sweep.string(), true);
  ASSERT_EQ(out.exit_code, 0) << out.text;
  for (const char* f : {"figure2", "figure3a", "figure3b"})
    for (const char* ext : {".png", ".pdf"})
      EXPECT_GT(std::filesystem::file_size(sweep / (std::string(f) + ext)), 1000u) << f << ext;
}

TEST_F(ReportCliTest, BadInputExitsTwoWithOneLine) {
  auto out = rapid_cli("summarize " + (scratch.path() / "nope").string(), true);
  EXPECT_EQ(out.exit_code, 2);
  EXPECT_NE(out.text.find("SWEEP_DIR"), std::string::npos) << out.text;
  EXPECT_EQ(std::count(out.text.begin(), out.text.end(), '\n'), 1) << out.text;
  out = rapid_cli("diff " + (scratch.path() / "nope").string() + " " + baseline.string(), true);
  EXPECT_EQ(out.exit_code, 2) << out.text;
  out = diff();  // the baseline file does not exist
  EXPECT_EQ(out.exit_code, 2) << out.text;
  EXPECT_NE(out.text.find("BASELINE"), std::string::npos) << out.text;
  ASSERT_EQ(write_baseline().exit_code, 0);
  out = diff(" --rtol -1");
  EXPECT_EQ(out.exit_code, 2) << out.text;
  EXPECT_NE(out.text.find("--rtol"), std::string::npos) << out.text;
  EXPECT_EQ(rapid_cli("summarize --help").exit_code, 0);
  EXPECT_EQ(rapid_cli("diff --help").exit_code, 0);

  // Issue #67: another grid's baseline is the wrong input, not a list of missing cells.
  nlohmann::json other = report_test::read_json(baseline);
  other["grid"] = "paper-flow";
  std::ofstream(baseline) << other.dump(1);
  out = diff();
  EXPECT_EQ(out.exit_code, 2) << out.text;
  EXPECT_NE(out.text.find("is grid paper-flow's baseline; "), std::string::npos) << out.text;
  EXPECT_EQ(std::count(out.text.begin(), out.text.end(), '\n'), 1) << out.text;
}

// Issue #67: a positional argument has one name, the one its help shows and its errors say
// ("sweep_dir" in the help, "SWEEP_DIR" in the errors before).
TEST(PositionalArguments, AreNamedInTheHelpAsTheirErrorsNameThem) {
  const std::map<std::string, std::string> first = {
      {"status", "SWEEP_DIR"}, {"summarize", "SWEEP_DIR"},  {"diff", "SWEEP_DIR"},        {"eval-budget", "SWEEP_DIR"},
      {"paper", "REPORTS_DIR"}, {"beside", "NOW"},          {"replay-decide", "FOLDER"},   {"simulate-decide", "FOLDER"},
      {"rerun", "DIR"},         {"budget", "DIR"},          {"sweep", "GRID"},             {"tune", "GRID"},
      {"recheck", "SWEEP_DIR"}};
  for (const auto& [command, name] : first) {
    const test::CliOutput none = rapid_cli(command, true);
    EXPECT_EQ(none.exit_code, 2) << command << ": " << none.text;
    EXPECT_NE(none.text.find(name + " is required"), std::string::npos) << command << ": " << none.text;
    const std::string help = rapid_cli(command + " --help").text;
    EXPECT_NE(help.find(name), std::string::npos) << command << ": " << help;
  }
  const test::CliOutput nowhere = rapid_cli("eval-budget /nonexistent-folder", true);
  EXPECT_EQ(nowhere.exit_code, 2) << nowhere.text;
  EXPECT_NE(nowhere.text.find("SWEEP_DIR: "), std::string::npos) << nowhere.text;
}

// simulate-decide and replay-decide read a folder and print what they find; they write a file only
// where --out says (issue #67: the committed decide-simulation.md was overwritten by a run that
// found 0 cells, with "-nan %" shares). Nothing to simulate is bad input; so is a NaN futility.
TEST_F(ReportCliTest, DecideAnalysesPrintAndWriteOnlyWhereAsked) {
  const std::filesystem::path committed = std::filesystem::path(RAPID_SOURCE_DIR) / "results" / "paper-flow-decided";
  const auto listing = [](const std::filesystem::path& dir) {
    std::map<std::string, std::uintmax_t> files;
    for (const auto& e : std::filesystem::directory_iterator(dir)) files[e.path().filename().string()] = e.file_size();
    return files;
  };
  const auto before = listing(committed);
  auto out = rapid_cli("simulate-decide " + committed.string() + " --experiments 2", true);
  ASSERT_EQ(out.exit_code, 0) << out.text;
  EXPECT_NE(out.text.find("cells seeds drawn"), std::string::npos) << out.text;
  EXPECT_NE(out.text.find("decided comparisons lost to futility"), std::string::npos) << out.text;
  EXPECT_EQ(out.text.find("nan"), std::string::npos) << out.text;
  EXPECT_EQ(out.text.find("inf %"), std::string::npos) << out.text;
  out = rapid_cli("replay-decide " + committed.string(), true);
  ASSERT_EQ(out.exit_code, 0) << out.text;
  EXPECT_EQ(listing(committed), before);  // the committed folder as it was
  const std::filesystem::path md = scratch.path() / "sim.md";
  out = rapid_cli("simulate-decide " + committed.string() + " --experiments 2 --out " + md.string(), true);
  ASSERT_EQ(out.exit_code, 0) << out.text;
  EXPECT_TRUE(std::filesystem::exists(md));

  // Issue #66: a folder run on fixed seeds replayed as if its first seeds were look 0 (the
  // confirmatory study's futility replay), with the decisions futility would have lost.
  const std::filesystem::path fixed_seeds = std::filesystem::path(RAPID_SOURCE_DIR) / "results" / "paper-flow-recheck";
  const auto fixed_before = listing(fixed_seeds);
  out = rapid_cli("replay-decide " + fixed_seeds.string() + " --initial-seeds 100-104 --max-seeds 10", true);
  ASSERT_EQ(out.exit_code, 0) << out.text;
  EXPECT_NE(out.text.find("the replay takes its first 5 seeds as look 0"), std::string::npos) << out.text;
  EXPECT_NE(out.text.find("| fixed, 10 seeds | 1 | 390 | 100 % |"), std::string::npos) << out.text;
  EXPECT_NE(out.text.find("Decisions lost to futility ("), std::string::npos) << out.text;
  EXPECT_EQ(listing(fixed_seeds), fixed_before);
  // The seeds as a list are the same seeds (one parser for recheck's --seeds and this option).
  EXPECT_EQ(rapid_cli("replay-decide " + fixed_seeds.string() + " --initial-seeds 100,101,102,103,104 --max-seeds 10", true).text,
            out.text);
  for (const std::string bad : {"replay-decide " + committed.string() + " --initial-seeds 0-9",
                                "replay-decide " + fixed_seeds.string() + " --initial-seeds 100,100",
                                "replay-decide " + committed.string() + " --block 3",
                                "replay-decide " + fixed_seeds.string() + " --initial-seeds 9-1",
                                "replay-decide " + fixed_seeds.string() + " --initial-seeds 100-109 --max-seeds 5",
                                "replay-decide " + fixed_seeds.string()}) {
    out = rapid_cli(bad, true);
    EXPECT_EQ(out.exit_code, 2) << bad << ": " << out.text;
    EXPECT_EQ(std::count(out.text.begin(), out.text.end(), '\n'), 1) << bad << ": " << out.text;
  }

  // A sweep folder with no ok seed: nothing to simulate, said in one line, nothing written.
  const std::filesystem::path empty = scratch.path() / "empty";
  report_test::write_grid(empty, report_test::make_grid("empty", {"pendulum"}, {"initial"}, {"rapid-rl", "ddpg"}, {0, 1}));
  std::filesystem::create_directories(empty / "jobs");
  out = rapid_cli("simulate-decide " + empty.string() + " --experiments 2 --out " + (scratch.path() / "e.md").string(), true);
  EXPECT_EQ(out.exit_code, 2) << out.text;
  EXPECT_NE(out.text.find("no cell with an ok seed"), std::string::npos) << out.text;
  EXPECT_EQ(std::count(out.text.begin(), out.text.end(), '\n'), 1) << out.text;
  EXPECT_FALSE(std::filesystem::exists(scratch.path() / "e.md"));

  for (const std::string bad : {"nan", "-0.1", "1", "inf", "0.1x", ""}) {
    for (const std::string cmd : {"simulate-decide " + sweep.string(), "replay-decide " + committed.string(),
                                  "sweep " + (sweep / "grid.json").string() + " --decide"}) {
      out = rapid_cli(cmd + " --futility '" + bad + "'", true);
      EXPECT_EQ(out.exit_code, 2) << cmd << " --futility " << bad << ": " << out.text;
      EXPECT_NE(out.text.find("--futility"), std::string::npos) << out.text;
    }
  }
  out = rapid_cli("simulate-decide " + sweep.string() + " --out ''", true);
  EXPECT_EQ(out.exit_code, 2) << out.text;
  // An empty --out is refused by every command that takes one (issue #67: tune and recheck fell
  // back to their default folder).
  for (const std::string cmd : {"tune " + (sweep / "grid.json").string() + " --space x.json", "recheck " + sweep.string() + " --seeds 100-101",
                                "replay-decide " + committed.string()}) {
    out = rapid_cli(cmd + " --out ''", true);
    EXPECT_EQ(out.exit_code, 2) << cmd << ": " << out.text;
    EXPECT_NE(out.text.find("--out"), std::string::npos) << cmd << ": " << out.text;
  }
  EXPECT_EQ(listing(committed), before);
}

// What a command prints is its output: when standard output cannot take it (a full disk, a closed
// pipe), the command fails with one line, never exit 0 with nothing written (issue #67).
TEST_F(ReportCliTest, AStandardOutputThatCannotBeWrittenIsAFailure) {
  const std::string results = std::string(RAPID_SOURCE_DIR) + "/results/";
  const std::string err = (scratch.path() / "err").string();
  for (const std::string args : {"paper " + results + "paper-flow", "status " + results + "paper-flow",
                                 "replay-decide " + results + "paper-flow-decided", "beside " + results + "paper-flow " +
                                 results + "paper-flow-decided", "run --print-config --scenario merge --algo ddpg --seed 0 --out " +
                                 (scratch.path() / "r").string()}) {
    const int raw = std::system((std::string(RAPID_BIN) + " " + args + " > /dev/full 2> " + err).c_str());
    ASSERT_TRUE(WIFEXITED(raw)) << args;
    EXPECT_EQ(WEXITSTATUS(raw), 1) << args;
    const std::string text = report_test::read_text(err);
    EXPECT_NE(text.find("could not write standard output"), std::string::npos) << args << ": " << text;
  }
}

// --write-baseline replaces only a regular file, in a folder it can write, and finds out before
// reading the sweep: the symlink, FIFO, device or folder named stays as it was.
TEST_F(ReportCliTest, WriteBaselineRefusesWhatIsNotARegularFileOrCannotBeWritten) {
  const auto at = [&](const std::string& name) { return (scratch.path() / name).string(); };
  report_test::write_text(at("mine.json"), "mine");
  std::filesystem::create_symlink(at("mine.json"), at("link.json"));
  ASSERT_TRUE(test::make_fifo(at("fifo.json")));
  std::filesystem::create_directories(at("folder.json"));
  std::vector<std::string> refused = {at("link.json"), at("fifo.json"), at("folder.json")};
  const bool device = test::make_device(at("null.json"));  // root only
  if (device) refused.push_back(at("null.json"));
  const test::ReadOnlyFolder read_only(scratch.path() / "read-only");
  if (read_only.usable()) refused.push_back(read_only / "baseline.json");
  for (const std::string& path : refused) {
    const auto out = rapid_cli("diff " + sweep.string() + " " + path + " --write-baseline", true);
    EXPECT_EQ(out.exit_code, 2) << path << "\n" << out.text;
    EXPECT_EQ(out.text.rfind("rapid: error: BASELINE: ", 0), 0u) << out.text;
    EXPECT_EQ(std::count(out.text.begin(), out.text.end(), '\n'), 1) << out.text;
  }
  EXPECT_TRUE(std::filesystem::is_symlink(at("link.json")));
  EXPECT_EQ(report_test::read_text(at("mine.json")), "mine");
  EXPECT_TRUE(test::is_fifo(at("fifo.json")));
  EXPECT_TRUE(std::filesystem::is_empty(at("folder.json")));
  if (device) {
    EXPECT_TRUE(test::is_device(at("null.json")));
  }
}

TEST_F(ReportCliTest, DiffPassesOnAnIdenticalSweep) {
  const auto written = write_baseline();
  ASSERT_EQ(written.exit_code, 0) << written.text;
  EXPECT_EQ(report_test::read_json(baseline)["schema"], "rapid.baseline/1");
  const auto out = diff();
  EXPECT_EQ(out.exit_code, 0) << out.text;
  EXPECT_NE(out.text.find("no differences in 5 cells"), std::string::npos) << out.text;
}

// --rtol inf accepts any finite difference, and certainly none: a cell whose std is 0 on both
// sides (inf · 0 is NaN) must not "differ beyond rtol".
TEST_F(ReportCliTest, DiffWithAnInfiniteRtolPassesOnAnIdenticalSweep) {
  for (std::uint64_t seed : {0u, 1u, 2u}) run("", "ddpg", seed, 50.0);  // std 0
  ASSERT_EQ(write_baseline().exit_code, 0);
  const auto out = diff(" --rtol inf");
  EXPECT_EQ(out.exit_code, 0) << out.text;
  EXPECT_NE(out.text.find("no differences in 5 cells"), std::string::npos) << out.text;
}

TEST_F(ReportCliTest, DiffFailsOnAChangedValue) {
  ASSERT_EQ(write_baseline().exit_code, 0);
  run("initial", "rapid-rl", 1, 110.001);
  const auto out = diff();
  EXPECT_EQ(out.exit_code, 1) << out.text;
  EXPECT_NE(out.text.find("pendulum/initial/rapid-rl"), std::string::npos) << out.text;
  EXPECT_NE(out.text.find("mean differs"), std::string::npos) << out.text;
  EXPECT_EQ(out.text.find("pendulum/final+medium/rapid-rl"), std::string::npos) << out.text;
  EXPECT_EQ(diff(" --rtol 1e-3").exit_code, 0);  // within a looser tolerance
}

TEST_F(ReportCliTest, DiffStatPassesInsideTheIntervalAndFailsOutside) {
  ASSERT_EQ(write_baseline().exit_code, 0);
  run("initial", "rapid-rl", 1, 112);  // mean 100,110,120 → 100,112,120: the baseline mean 110 is inside the CI
  EXPECT_EQ(diff().exit_code, 1);
  auto out = diff(" --stat");
  EXPECT_EQ(out.exit_code, 0) << out.text;
  for (std::uint64_t seed : {0u, 1u, 2u}) run("initial", "rapid-rl", seed, 500.0 + seed);
  out = diff(" --stat");
  EXPECT_EQ(out.exit_code, 1) << out.text;
  EXPECT_NE(out.text.find("outside the new 95% interval"), std::string::npos) << out.text;
}

TEST_F(ReportCliTest, DiffFailsOnAFailedSeed) {
  ASSERT_EQ(write_baseline().exit_code, 0);
  run("", "ddpg", 1, 0, "diverged");
  const auto out = diff(" --stat");
  EXPECT_EQ(out.exit_code, 1) << out.text;
  EXPECT_NE(out.text.find("ok seeds 3/3 → 2/3"), std::string::npos) << out.text;
}

TEST_F(ReportCliTest, DiffFailsOnACellMissingOnEitherSide) {
  ASSERT_EQ(write_baseline().exit_code, 0);
  nlohmann::json b = report_test::read_json(baseline);
  const nlohmann::json dropped = b["cells"][0];
  b["cells"].erase(0);
  nlohmann::json extra = dropped;
  extra["cell"] = "pendulum/final/rapid-rl";
  b["cells"].push_back(extra);
  report_test::write_text(baseline, b.dump());
  const auto out = diff();
  EXPECT_EQ(out.exit_code, 1) << out.text;
  EXPECT_NE(out.text.find(dropped["cell"].get<std::string>()), std::string::npos) << out.text;
  EXPECT_NE(out.text.find("missing from the baseline"), std::string::npos) << out.text;
  EXPECT_NE(out.text.find("pendulum/final/rapid-rl"), std::string::npos) << out.text;
  EXPECT_NE(out.text.find("missing from the sweep"), std::string::npos) << out.text;
  // The sweep's cells and the one only the baseline has: two of them differ.
  const std::string count = "2 of " + std::to_string(b["cells"].size() + 1) + " cells differ";
  EXPECT_NE(out.text.find(count), std::string::npos) << out.text;
}

TEST_F(ReportCliTest, DiffFailsOnAWrongSchema) {
  ASSERT_EQ(write_baseline().exit_code, 0);
  nlohmann::json b = report_test::read_json(baseline);
  b["schema"] = "rapid.baseline/0";
  report_test::write_text(baseline, b.dump());
  auto out = diff();
  EXPECT_EQ(out.exit_code, 1) << out.text;
  EXPECT_NE(out.text.find("schema mismatch"), std::string::npos) << out.text;
  // A summary.json is not a baseline either.
  ASSERT_EQ(rapid_cli("summarize " + sweep.string() + " --no-plots").exit_code, 0);
  out = rapid_cli("diff " + sweep.string() + " " + (sweep / "summary.json").string(), true);
  EXPECT_EQ(out.exit_code, 1) << out.text;
  EXPECT_NE(out.text.find("schema mismatch"), std::string::npos) << out.text;
}

// `rapid paper`: the paper beside a reports folder, the same text as the end of its table.md (the
// committed paper-flow folder's, whose records are not in git), and a clear line for a folder that
// has nothing to set beside the paper or no summary.
TEST_F(ReportCliTest, PaperSetsTheFolderBesideThePapersTableI) {
  const std::filesystem::path paper_flow = std::filesystem::path(RAPID_SOURCE_DIR) / "results" / "paper-flow";
  const test::CliOutput r = rapid_cli("paper " + paper_flow.string(), true);
  ASSERT_EQ(r.exit_code, 0) << r.text;
  EXPECT_NE(r.text.find("## The paper beside us"), std::string::npos) << r.text;
  EXPECT_NE(r.text.find("| Lane-drop | Initial | RAPID-RL 939.7 > RLPD 765.4"), std::string::npos) << r.text;
  const std::string table = report_test::read_text(paper_flow / "table.md");
  ASSERT_GE(table.size(), r.text.size());
  EXPECT_EQ(table.substr(table.size() - r.text.size()), r.text) << "table.md ends with the same section";

  ASSERT_EQ(rapid_cli("summarize " + sweep.string() + " --no-plots").exit_code, 0);
  const test::CliOutput pendulum = rapid_cli("paper " + sweep.string(), true);
  EXPECT_EQ(pendulum.exit_code, 0) << pendulum.text;
  EXPECT_NE(pendulum.text.find("nothing to set beside the paper"), std::string::npos) << pendulum.text;
  EXPECT_EQ(report_test::read_text(sweep / "table.md").find("The paper beside us"), std::string::npos);

  const test::CliOutput empty = rapid_cli("paper " + scratch.path().string(), true);
  EXPECT_EQ(empty.exit_code, 2);
  EXPECT_NE(empty.text.find("REPORTS_DIR: " + (scratch.path() / "summary.json").string()), std::string::npos) << empty.text;
}

}  // namespace
}  // namespace rapid
