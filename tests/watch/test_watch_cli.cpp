// `rapid rollout --record / --settings-from / --eval-traffic` as users run them, and the watch
// options' bad input: exit 2, one line naming the option, nothing written.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "tests/special_files.hpp"
#include "tests/watch/watch_test_util.hpp"

namespace rapid {
namespace {

using test::rapid;
using test::run_shell;
using test::Scratch;

TEST(WatchCli, SameSeedByteIdenticalTraceAcrossProcesses) {
  Scratch s;
  const std::string common = "rollout --scenario merge --policy random --episodes 2 --record ";
  ASSERT_EQ(run_shell(rapid(common + s / "a.json --seed 4")).exit_code, 0);
  ASSERT_EQ(run_shell(rapid(common + s / "b.json --seed 4")).exit_code, 0);
  ASSERT_EQ(run_shell(rapid(common + s / "c.json --seed 5")).exit_code, 0);
  const std::string a = test::slurp(s / "a.json");
  ASSERT_FALSE(a.empty());
  EXPECT_EQ(a, test::slurp(s / "b.json"));
  EXPECT_NE(a, test::slurp(s / "c.json"));
  // No machine-specific content: no temporary file names, no host, no absolute paths.
  EXPECT_EQ(a.find("/tmp"), std::string::npos);
  EXPECT_EQ(test::entries(s.dir), 3) << "a temporary file was left behind";
}

TEST(WatchCli, TraceReturnsAreTheRolloutsReturns) {
  Scratch s;
  const test::Run r = run_shell(rapid("rollout --scenario lane-drop --policy random --episodes 3 --seed 2 --json --record " +
                                      s / "t.json"),
                                /*with_stderr=*/false);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const auto printed = nlohmann::json::parse(r.out);
  const auto trace = nlohmann::json::parse(test::slurp(s / "t.json"));
  EXPECT_EQ(trace["schema"], "rapid.trace/1");
  EXPECT_EQ(trace["scenario"], "lane-drop");
  EXPECT_EQ(trace["policy"], "random");
  EXPECT_EQ(trace["seed"], 2);
  EXPECT_EQ(trace["traffic"], "seed");
  ASSERT_EQ(trace["episodes"].size(), 3u);
  for (int e = 0; e < 3; ++e) {
    const auto& ep = trace["episodes"][e];
    EXPECT_EQ(ep["index"], e);
    double sum = 0;
    for (const auto& d : ep["decisions"]) sum += d["reward"].get<float>();
    EXPECT_EQ(sum, printed["episodes"][e]["return"].get<double>()) << "episode " << e;
    EXPECT_EQ(ep["return"].get<double>(), printed["episodes"][e]["return"].get<double>());
    EXPECT_EQ(ep["length"], printed["episodes"][e]["length"]);
    EXPECT_EQ(ep["collision"], printed["episodes"][e]["collision"]);
  }
}

TEST(WatchCli, EvalTrafficIsTheTrainersEvaluationEpisode) {
  Scratch s;
  const std::string cmd = "rollout --scenario merge --policy zero --episodes 1 --eval-traffic --record ";
  ASSERT_EQ(run_shell(rapid(cmd + s / "a.json --seed 1")).exit_code, 0);
  ASSERT_EQ(run_shell(rapid(cmd + s / "b.json --seed 2")).exit_code, 0);
  const auto a = nlohmann::json::parse(test::slurp(s / "a.json"));
  const auto b = nlohmann::json::parse(test::slurp(s / "b.json"));
  EXPECT_EQ(a["traffic"], "evaluation");
  // The traffic no longer depends on --seed.
  EXPECT_EQ(a["episodes"][0]["env_seed"], b["episodes"][0]["env_seed"]);
  EXPECT_EQ(a["episodes"][0]["decisions"], b["episodes"][0]["decisions"]);
}

// A run record whose config carries the flow profile's scenario keys (shortened horizon).
std::string write_flow_record(const Scratch& s, const std::string& scenario, int horizon) {
  // The flow profile's keys shared by its scenarios, then merge's own (as the harness layers them).
  const std::string source = RAPID_SOURCE_DIR;
  nlohmann::json config = nlohmann::json::parse(test::slurp(source + "/experiments/configs/flow/shared.json"));
  config.update(nlohmann::json::parse(test::slurp(source + "/envs/networks/merge/scenario.json"))["profiles"]["flow"]);
  config["horizon"] = horizon;
  const nlohmann::json record = {{"schema", "rapid.run/1"},
                                 {"cell", {{"scenario", scenario}, {"algo", "ddpg"}, {"dataset", nullptr}, {"seed", 0}}},
                                 {"status", "ok"},
                                 {"config", config}};
  std::filesystem::create_directories(s.dir / "run");
  test::spit(s / "run/record.json", record.dump());
  return s / "run";
}

TEST(WatchCli, SettingsFromARunRecord) {
  Scratch s;
  const std::string run = write_flow_record(s, "merge", 30);
  const test::Run r = run_shell(rapid("rollout --scenario merge --policy sumo --episodes 1 --settings-from " + run +
                                      " --record " + s / "t.json --json"),
                                false);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const auto trace = nlohmann::json::parse(test::slurp(s / "t.json"));
  EXPECT_EQ(trace["settings"]["network"], "long");
  EXPECT_EQ(trace["settings"]["reward"], "flow");
  EXPECT_EQ(trace["settings"]["action_repeat"], 1);
  EXPECT_EQ(trace["settings"]["horizon"], 30);
  EXPECT_EQ(trace["decision_seconds"], 0.1);
  EXPECT_EQ(trace["reward_weights"]["offset"], 0.3);
  EXPECT_LE(trace["episodes"][0]["length"].get<int>(), 30);
}

// Bad input: exit 2, exactly one line "rapid: error: <option>: …", and nothing written.
void expect_usage_error(const std::string& args, const std::string& option, const Scratch& s,
                        const std::string& env = "") {
  const int before = test::entries(s.dir);
  const test::Run r = run_shell(env + rapid(args));
  EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.out;
  EXPECT_EQ(test::count_lines(r.out), 1) << r.out;
  EXPECT_EQ(r.out.rfind("rapid: error: " + option + ":", 0), 0u) << r.out;
  EXPECT_EQ(test::entries(s.dir), before) << "bad input wrote something: " << args;
}

TEST(WatchCli, BadInputIsOneLineAndWritesNothing) {
  Scratch s;
  const std::string t = s / "t.json";
  expect_usage_error("rollout --scenario merge --policy sumo --record " + s / "missing/t.json", "--record", s);
  expect_usage_error("rollout --scenario merge --policy sumo --record " + s.dir.string(), "--record", s);
  expect_usage_error("rollout --scenario pendulum --policy zero --record " + t, "--record", s);
  expect_usage_error("rollout --scenario merge --policy sumo --gui --record " + t, "--gui", s, "env -u DISPLAY ");
  expect_usage_error("rollout --scenario merge --policy sumo --gui --record " + t, "--gui", s, "DISPLAY=:97 ");
  expect_usage_error("rollout --scenario pendulum --policy zero --gui", "--gui", s);
  expect_usage_error("rollout --scenario merge --policy sumo --screenshot " + s / "x.png", "--screenshot", s);
  expect_usage_error("rollout --scenario merge --policy sumo --gui --screenshot " + s / "missing/x.png", "--screenshot", s);
  expect_usage_error("rollout --scenario merge --policy sumo --settings-from " + s / "nope.json", "--settings-from", s);
  test::spit(s / "not-a-record.json", R"({"schema":"rapid.summary/1"})");
  expect_usage_error("rollout --scenario merge --policy sumo --settings-from " + s / "not-a-record.json", "--settings-from", s);
  const std::string other = write_flow_record(s, "lane-drop", 30);
  expect_usage_error("rollout --scenario merge --policy sumo --settings-from " + other + " --record " + t,
                     "--settings-from", s);
  expect_usage_error("rollout --scenario motorway --policy sumo --record " + t, "--scenario", s);
}

// An output path that exists but is not a regular file, or whose folder cannot be written, is
// bad input found before the rollout: the symlink, FIFO or device stays as it was.
TEST(WatchCli, ARecordThatIsNotARegularFileOrCannotBeWrittenIsRefused) {
  Scratch s;
  test::spit(s / "mine.json", "mine");
  std::filesystem::create_symlink(s / "mine.json", s / "link.json");
  ASSERT_TRUE(test::make_fifo(s / "fifo.json"));
  const bool device = test::make_device(s / "null.json");  // root only
  const test::ReadOnlyFolder read_only(s.dir / "read-only");
  const std::string args = "rollout --scenario merge --policy zero --episodes 1 --record ";
  expect_usage_error(args + s / "link.json", "--record", s);
  expect_usage_error(args + s / "fifo.json", "--record", s);
  if (device) expect_usage_error(args + s / "null.json", "--record", s);
  if (read_only.usable()) {
    expect_usage_error(args + read_only / "t.json", "--record", s);
  }
  EXPECT_TRUE(std::filesystem::is_symlink(s / "link.json"));
  EXPECT_EQ(test::slurp(s / "mine.json"), "mine");
  EXPECT_TRUE(test::is_fifo(s / "fifo.json"));
  if (device) {
    EXPECT_TRUE(test::is_device(s / "null.json"));
  }
  EXPECT_EQ(run_shell(rapid(args + s / "fifo.json")).out,
            "rapid: error: --record: '" + s / "fifo.json" + "' is a FIFO, not a regular file; name a new or regular file\n");
}

// Inputs that are not regular files end with a message instead of reading forever (issue 46: a
// FIFO as --policy or --settings-from blocked, /dev/zero as --policy read until memory ran out).
// `timeout` turns a hang back into a failure of this test.
TEST(WatchCli, InputsThatAreNotRegularFilesAreRefusedNotReadForever) {
  Scratch s;
  ASSERT_TRUE(test::make_fifo(s / "fifo.ckpt"));
  ASSERT_TRUE(test::make_fifo(s / "fifo.json"));
  expect_usage_error("rollout --scenario merge --policy " + s / "fifo.ckpt" + " --episodes 1", "--policy", s, "timeout 60 ");
  expect_usage_error("rollout --scenario merge --policy zero --episodes 1 --settings-from " + s / "fifo.json",
                     "--settings-from", s, "timeout 60 ");
  const test::Run r = run_shell("timeout 60 " + rapid("rollout --scenario merge --policy /dev/zero --episodes 1"));
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_NE(r.out.find("is a device, not a regular file"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace rapid
