// `scripts/plot animate` (Debian's /usr/bin/python3, docs/traces.md): a recorded episode becomes a
// GIF or a PNG frame; a bad trace is refused with exit 2 and one line "plot animate: <file>: …",
// and nothing is written.
#include <gtest/gtest.h>

#include <filesystem>

#include <nlohmann/json.hpp>

#include "tests/special_files.hpp"
#include "tests/watch/watch_test_util.hpp"

namespace rapid {
namespace {

using test::run_shell;
using test::Scratch;

const std::string kPlot = std::string(RAPID_SOURCE_DIR) + "/scripts/plot";

std::string animate(const std::string& args) { return "/usr/bin/python3 " + kPlot + " animate " + args; }

bool has_drawing_stack() { return run_shell("/usr/bin/python3 -c 'import matplotlib, PIL'").exit_code == 0; }

class AnimateCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    scratch_ = new Scratch;
    trace_ = *scratch_ / "merge.json";
    const test::Run r = run_shell(test::rapid("rollout --scenario merge --policy sumo --episodes 2 --seed 3 --record " + trace_));
    ASSERT_EQ(r.exit_code, 0) << r.out;
    text_ = test::slurp(trace_);
  }
  static void TearDownTestSuite() { delete scratch_; }

  // Writes `text` as a trace file and expects animate to refuse it with `problem` in its one line.
  void expect_refused(const std::string& name, const std::string& text, const std::string& problem,
                      const std::string& extra = "") {
    const std::string path = *scratch_ / name;
    test::spit(path, text);
    expect_refused_file(path, problem, extra);
  }
  void expect_refused_file(const std::string& path, const std::string& problem, const std::string& extra = "") {
    const std::string out = *scratch_ / "out.gif";
    const test::Run r = run_shell(animate(path + " -o " + out + " " + extra), true, /*stderr_only=*/true);
    EXPECT_EQ(r.exit_code, 2) << path << ": " << r.out;
    EXPECT_EQ(test::count_lines(r.out), 1) << r.out;
    EXPECT_EQ(r.out.rfind("plot animate: " + path + ": ", 0), 0u) << r.out;
    EXPECT_NE(r.out.find(problem), std::string::npos) << "expected '" << problem << "' in: " << r.out;
    EXPECT_FALSE(std::filesystem::exists(out)) << "a refused trace was drawn";
  }
  nlohmann::json parsed() const { return nlohmann::json::parse(text_); }

  static Scratch* scratch_;
  static std::string trace_, text_;
};
Scratch* AnimateCli::scratch_ = nullptr;
std::string AnimateCli::trace_, AnimateCli::text_;

TEST_F(AnimateCli, DrawsAGifAndAFrame) {
  if (!has_drawing_stack()) GTEST_SKIP() << "/usr/bin/python3 lacks matplotlib or Pillow (python3-matplotlib python3-pil)";
  const std::string gif = *scratch_ / "merge.gif", png = *scratch_ / "frame.png";
  test::Run r = run_shell(animate(trace_ + " -o " + gif + " --max-frames 12 --episode 1 --scenario merge"));
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_EQ(test::slurp(gif).substr(0, 6), "GIF89a");
  // At most --max-frames frames.
  r = run_shell("/usr/bin/python3 -c 'from PIL import Image; im = Image.open(\"" + gif + "\"); print(im.n_frames)'");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_GE(std::stoi(r.out), 2);
  EXPECT_LE(std::stoi(r.out), 12);
  r = run_shell(animate(trace_ + " -o " + png + " --frame 30"));
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_EQ(test::slurp(png).substr(1, 3), "PNG");
}

// The plots never write through a symlink or into a FIFO at an output's name (issue 46: a symlinked
// animation or figure had its target replaced, a FIFO hung the plot or gave a traceback): one
// line, exit 2, the user's file untouched; figures are checked before any is drawn.
TEST_F(AnimateCli, PlotsRefuseOutputsThatAreNotRegularFiles) {
  if (!has_drawing_stack()) GTEST_SKIP() << "/usr/bin/python3 lacks matplotlib or Pillow (python3-matplotlib python3-pil)";
  const std::string dir = *scratch_ / "special";
  std::filesystem::create_directories(dir);
  test::spit(dir + "/victim", "precious");
  std::filesystem::create_symlink(dir + "/victim", dir + "/linked.gif");
  test::Run r = run_shell(animate(trace_ + " -o " + dir + "/linked.gif --max-frames 4"), true, /*stderr_only=*/true);
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_EQ(test::count_lines(r.out), 1) << r.out;
  EXPECT_NE(r.out.find("is a symlink, not a regular file"), std::string::npos) << r.out;
  EXPECT_EQ(test::slurp(dir + "/victim"), "precious");
  ASSERT_TRUE(test::make_fifo(dir + "/fifo.png"));
  r = run_shell(animate(trace_ + " -o " + dir + "/fifo.png"), true, /*stderr_only=*/true);
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_NE(r.out.find("is a FIFO, not a regular file"), std::string::npos) << r.out;

  // scripts/plot: a symlinked figure3b.pdf is refused before figure2 is drawn.
  const std::string figures = *scratch_ / "figures";
  std::filesystem::create_directories(figures);
  test::spit(figures + "/summary.json",
             R"({"schema": "rapid.summary/1", "algorithms": [], "grid": {"scenarios": [], "datasets": [], "algos": []}, "cells": [], "rows": []})");
  std::filesystem::create_symlink(dir + "/victim", figures + "/figure3b.pdf");
  r = run_shell("/usr/bin/python3 " + kPlot + " --summary " + figures + "/summary.json", true, /*stderr_only=*/true);
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_EQ(test::count_lines(r.out), 1) << r.out;
  EXPECT_NE(r.out.find("figure3b.pdf is a symlink, not a regular file"), std::string::npos) << r.out;
  EXPECT_EQ(test::slurp(dir + "/victim"), "precious");
  EXPECT_FALSE(std::filesystem::exists(figures + "/figure2.png")) << "nothing is drawn when an output is refused";
}

TEST_F(AnimateCli, RefusesUnreadableAndTruncatedFiles) {
  expect_refused_file(*scratch_ / "missing.json", "cannot read it");
  expect_refused("truncated.json", text_.substr(0, text_.size() / 2), "not valid JSON (truncated?)");
  expect_refused("garbage.json", "not json at all", "not valid JSON");
  expect_refused("array.json", "[1, 2]", "not a JSON object");
}

TEST_F(AnimateCli, RefusesOtherSchemasAndVersions) {
  auto j = parsed();
  j["schema"] = "rapid.trace/2";
  expect_refused("v2.json", j.dump(), "format version '2' is not supported");
  j["schema"] = "rapid.summary/1";
  expect_refused("summary.json", j.dump(), "schema is 'rapid.summary/1', expected 'rapid.trace/1'");
  j.erase("schema");
  expect_refused("noschema.json", j.dump(), "no 'schema' field");
}

TEST_F(AnimateCli, RefusesMissingFieldsAndLengthsThatDisagree) {
  auto j = parsed();
  j.erase("episodes");
  expect_refused("noepisodes.json", j.dump(), "missing field 'episodes'");
  j = parsed();
  j["episodes"][0]["length"] = j["episodes"][0]["length"].get<int>() + 1;
  expect_refused("length.json", j.dump(), "but " + std::to_string(j["episodes"][0]["decisions"].size()) + " decisions");
  j = parsed();
  j["episodes"][0]["decisions"][3]["vehicles"].push_back({"x", "human", "acc_1", 1.0});
  expect_refused("row.json", j.dump(), "vehicle row");
  j = parsed();
  j["episodes"][0]["decisions"][2]["reward"] = "high";
  expect_refused("type.json", j.dump(), "field 'reward' is not a number");
  j = parsed();
  j["episodes"][0]["decisions"].erase(5);
  j["episodes"][0]["length"] = j["episodes"][0]["decisions"].size();
  expect_refused("gap.json", j.dump(), "t is 6, expected 5");
}

TEST_F(AnimateCli, RefusesATraceOfAnotherScenario) {
  // What the caller expects (rapid summarize passes --scenario).
  expect_refused_file(trace_, "is a trace of scenario 'merge', expected 'lane-drop'", "--scenario lane-drop");
  // A trace whose road is not its scenario's: recorded elsewhere, or its scenario edited.
  auto j = parsed();
  j["scenario"] = "cut-in";
  expect_refused("relabelled.json", j.dump(), "are not the cut-in road's");
}

TEST_F(AnimateCli, RefusesAnEpisodeItDoesNotHold) {
  expect_refused_file(trace_, "has no episode 7", "--episode 7");
}

}  // namespace
}  // namespace rapid
