// `rapid bench --quick` runs and writes a JSON object with the keys docs/performance.md names. Speed itself is
// never asserted: the machines are shared and noisy (docs/design.md §Performance rules: a benchmark, not a timed test).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "tests/special_files.hpp"

#ifndef RAPID_BIN
#error "RAPID_BIN must name the built rapid binary"
#endif

namespace fs = std::filesystem;

namespace {

int run(const std::string& args) {
  const std::string cmd = std::string("'") + RAPID_BIN + "' " + args + " > /dev/null 2>&1";
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

fs::path temp_file(const std::string& name) {
  return fs::temp_directory_path() / ("rapid-bench-test-" + std::to_string(::getpid()) + "-" + name);
}

}  // namespace

TEST(RapidBench, QuickRunWritesEveryKey) {
  const fs::path out = temp_file("quick.json");
  ASSERT_EQ(run("bench --quick --json '" + out.string() + "'"), 0);
  std::ifstream in(out);
  const nlohmann::json j = nlohmann::json::parse(in);
  fs::remove(out);

  for (const char* s : {"lane-drop", "cut-in", "merge"}) {
    ASSERT_TRUE(j["scenarios"].contains(s)) << s;
    for (const char* key : {"sumo_steps_per_s", "env_decisions_per_s", "env_overhead_ratio", "train_steps_per_s",
                            "end_to_end_ratio", "predicted_train_steps_per_s", "train_alone_decision_us",
                            "train_in_run_decision_us", "train_alone_update_us", "train_in_run_update_us"}) {
      ASSERT_TRUE(j["scenarios"][s].contains(key)) << s << "." << key;
      EXPECT_TRUE(j["scenarios"][s][key].is_number()) << s << "." << key;
    }
  }
  for (const char* a : {"rapid-rl", "rlpd", "col-prior", "col-all", "ddpg", "rapid-rl-return"}) {
    ASSERT_TRUE(j["algorithms"].contains(a)) << a;
    for (const char* key : {"updates_per_s", "update_gflops", "gemm_gflops"})
      EXPECT_TRUE(j["algorithms"][a][key].is_number()) << a << "." << key;
  }
  EXPECT_TRUE(j["machine"].contains("cpu"));
  EXPECT_TRUE(j.contains("sweep"));
}

TEST(RapidBench, OneScenarioAndPendulumWork) {
  const fs::path out = temp_file("pendulum.json");
  ASSERT_EQ(run("bench --quick --scenario pendulum --json '" + out.string() + "'"), 0);
  std::ifstream in(out);
  const nlohmann::json j = nlohmann::json::parse(in);
  fs::remove(out);
  ASSERT_EQ(j["scenarios"].size(), 1u);
  // No SUMO under the pendulum: its raw-SUMO fields are null, not made up.
  EXPECT_TRUE(j["scenarios"]["pendulum"]["sumo_steps_per_s"].is_null());
  EXPECT_TRUE(j["scenarios"]["pendulum"]["env_decisions_per_s"].is_number());
}

// The flow profile's scenarios (0.1 s decisions, one SUMO step each) and network sizes.
TEST(RapidBench, TheFlowProfileIsMeasuredAtItsOwnSettings) {
  const fs::path out = temp_file("flow.json");
  ASSERT_EQ(run("bench --quick --no-sweep --profile flow --scenario merge --json '" + out.string() + "'"), 0);
  std::ifstream in(out);
  const nlohmann::json j = nlohmann::json::parse(in);
  fs::remove(out);
  EXPECT_EQ(j["profile"], "flow");
  EXPECT_EQ(j["scenarios"]["merge"]["action_repeat"], 1);  // the short profile's is 5
  // The short profile's merge networks are 128 wide with batches of 128.
  EXPECT_EQ(j["algorithms"]["ddpg"]["shape"], "actor 18-64-64-2, critic 20-64-64-1, batch 64");
}

TEST(RapidBench, BadInputExitsTwo) {
  EXPECT_EQ(run("bench --quick --profile nope"), 2);
  EXPECT_EQ(run("bench --quick --profile flow --scenario pendulum"), 2);
  EXPECT_EQ(run("bench --quick --scenario nowhere"), 2);
  EXPECT_EQ(run("bench --quick --train-algo nothing"), 2);
  // It trains on the config files as they are, which have no return_horizon.
  EXPECT_EQ(run("bench --quick --train-algo rapid-rl-return"), 2);
}

// --json names a file it can write, checked before the minutes of measuring: not a FIFO or a
// symlink (which would be replaced), not in a read-only folder.
TEST(RapidBench, AJsonFileThatCannotBeWrittenIsRefusedFirst) {
  const fs::path dir = temp_file("outputs");
  fs::create_directories(dir);
  std::ofstream(dir / "mine.json") << "mine";
  fs::create_symlink(dir / "mine.json", dir / "link.json");
  ASSERT_TRUE(rapid::test::make_fifo((dir / "fifo.json").string()));
  const std::string args = "bench --quick --no-sweep --scenario pendulum --json ";
  EXPECT_EQ(run(args + (dir / "link.json").string()), 2);
  EXPECT_EQ(run(args + (dir / "fifo.json").string()), 2);
  {
    const rapid::test::ReadOnlyFolder read_only(dir / "read-only");
    if (read_only.usable()) EXPECT_EQ(run(args + (read_only / "bench.json")), 2);
  }
  EXPECT_TRUE(fs::is_symlink(dir / "link.json"));
  EXPECT_TRUE(rapid::test::is_fifo((dir / "fifo.json").string()));
  fs::remove_all(dir);
}
