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

// `rapid bench ARGS --json FILE`'s JSON, the file removed; null if the command failed.
nlohmann::json bench_json(const std::string& args, const std::string& name) {
  const fs::path out = temp_file(name);
  const int code = run(args + " --json '" + out.string() + "'");
  if (code != 0) return nullptr;
  std::ifstream in(out);
  nlohmann::json j = nlohmann::json::parse(in);
  fs::remove(out);
  return j;
}

}  // namespace

TEST(RapidBench, QuickRunWritesEveryKey) {
  const nlohmann::json j = bench_json("bench --quick", "quick.json");
  ASSERT_FALSE(j.is_null()) << "rapid bench failed";

  for (const char* s : {"lane-drop", "cut-in", "merge"}) {
    ASSERT_TRUE(j["scenarios"].contains(s)) << s;
    for (const char* key : {"sumo_steps_per_s", "env_decisions_per_s", "env_overhead_ratio", "train_steps_per_s",
                            "end_to_end_ratio", "predicted_train_steps_per_s", "train_alone_decision_us",
                            "train_in_run_decision_us", "train_alone_update_us", "train_in_run_update_us",
                            "full_episode_decision_us", "full_episode_decisions"}) {
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
  const nlohmann::json j = bench_json("bench --quick --scenario pendulum", "pendulum.json");
  ASSERT_FALSE(j.is_null()) << "rapid bench failed";
  ASSERT_EQ(j["scenarios"].size(), 1u);
  // No SUMO under the pendulum: its raw-SUMO fields are null, not made up.
  EXPECT_TRUE(j["scenarios"]["pendulum"]["sumo_steps_per_s"].is_null());
  EXPECT_TRUE(j["scenarios"]["pendulum"]["env_decisions_per_s"].is_number());
}

// The flow profile's scenarios (0.1 s decisions, one SUMO step each) and network sizes.
TEST(RapidBench, TheFlowProfileIsMeasuredAtItsOwnSettings) {
  const nlohmann::json j = bench_json("bench --quick --no-sweep --profile flow --scenario merge", "flow.json");
  ASSERT_FALSE(j.is_null()) << "rapid bench failed";
  EXPECT_EQ(j["profile"], "flow");
  EXPECT_EQ(j["scenarios"]["merge"]["action_repeat"], 1);  // the short profile's is 5
  // The short profile's merge networks are 128 wide with batches of 128.
  EXPECT_EQ(j["algorithms"]["ddpg"]["shape"], "actor 18-64-64-2, critic 20-64-64-1, batch 64");
  // A run is priced at the decision cost of whole episodes, not of the random ones, which collide
  // early on a road still filling with traffic: two episodes under SUMO's driver, each to the
  // horizon of 1,500 decisions (it does not crash), and every run cost's evaluation at that price.
  const nlohmann::json& merge = j["scenarios"]["merge"];
  EXPECT_EQ(merge["full_episode_decisions"], 2 * 1500);
  const double whole_s = merge["full_episode_decision_us"].get<double>() * 1e-6;
  ASSERT_FALSE(j["run_costs"].empty());
  for (const nlohmann::json& c : j["run_costs"])
    EXPECT_NEAR(c["eval_s_max"].get<double>(), c["eval_decisions_max"].get<double>() * whole_s, 1e-9) << c["algo"];
}

// The update's GEMMs are recorded as they run, so each algorithm's count is what its update rule
// says. In units of 2·B multiply-adds (B = 64), with layers actor 18-64-64-2 (rlpd-sac: 18-64-64-4,
// means and log stds) and critic 20-64-64-1: an actor forward is 5376 (rlpd-sac 5504), a critic
// forward 5440, a critic's weight gradients 5440 and its input gradients past the first layer
// 4160 (all three layers: 5440), an actor's weight gradients plus its inner input gradients 9600
// (rlpd-sac 9856).
TEST(RapidBench, EachAlgorithmsUpdateIsCountedAsItsRuleSays) {
  const nlohmann::json j = bench_json("bench --quick --no-sweep --profile flow --scenario merge", "gemms.json");
  ASSERT_FALSE(j.is_null()) << "rapid bench failed";
  const double unit = 2.0 * 64;
  // DDPG: actor forward, critic forward and its input gradients, the actor's gradients; then the
  // target actor and critic, the critic and its weight gradients.
  const auto flops = [&](const char* algo) { return j["algorithms"][algo]["flops_per_update"].get<double>(); };
  EXPECT_DOUBLE_EQ(flops("ddpg"), unit * (5376 + 5440 + 5440 + 9600 + 5376 + 5440 + 5440 + 9600));
  // TD3+BC: every step the target actor, both target critics, both critics and their gradients;
  // every second step the actor against the first critic.
  EXPECT_EQ(j["algorithms"]["td3-bc"]["cycle"], 2);
  EXPECT_DOUBLE_EQ(flops("td3-bc"), unit * (5376 + 2 * 5440 + 2 * 5440 + 2 * 9600 + (5376 + 5440 + 5440 + 9600) / 2.0));
  // RLPD: 10 critics, a target over 2 of them, 20 critic steps per actor step against all 10.
  EXPECT_EQ(j["algorithms"]["rlpd-sac"]["critics"], 10);
  EXPECT_EQ(j["algorithms"]["rlpd-sac"]["cycle"], 20);
  EXPECT_DOUBLE_EQ(flops("rlpd-sac"),
                   unit * (5504 + 2 * 5440 + 10 * 5440 + 10 * 9600 + (5504 + 10 * 5440 + 10 * 5440 + 9856) / 20.0));
  // One run's cost: rlpd-sac learns 20 times per decision, the paper's five once.
  bool saw_rlpd_sac = false;
  for (const nlohmann::json& c : j["run_costs"]) {
    ASSERT_EQ(c["scenario"], "merge");
    EXPECT_GT(c["train_s"].get<double>(), 0.0) << c["algo"];
    EXPECT_GT(c["eval_decisions_max"].get<long>(), 0) << c["algo"];
    const long per_decision = c["algo"] == "rlpd-sac" ? 20 : 1;
    EXPECT_EQ(c["learning_steps"].get<long>(), per_decision * c["decisions"].get<long>()) << c["algo"];
    saw_rlpd_sac = saw_rlpd_sac || c["algo"] == "rlpd-sac";
  }
  EXPECT_TRUE(saw_rlpd_sac);
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
    if (read_only.usable()) {
      EXPECT_EQ(run(args + (read_only / "bench.json")), 2);
    }
  }
  EXPECT_TRUE(fs::is_symlink(dir / "link.json"));
  EXPECT_TRUE(rapid::test::is_fifo((dir / "fifo.json").string()));
  fs::remove_all(dir);
}
