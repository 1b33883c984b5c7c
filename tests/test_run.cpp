// `rapid run` as a user runs it: records, determinism, divergence and bad input.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "algos/registry.hpp"
#include "core/atomic_file.hpp"
#include "core/dataset.hpp"
#include "core/dataset_io.hpp"
#include "core/mlp.hpp"
#include "envs/env.hpp"
#include "envs/pendulum.hpp"
#include "experiments/cli/commands.hpp"
#include "experiments/run/run_config.hpp"
#include "tests/cli_runner.hpp"
#include "tests/datasets/dataset_fixtures.hpp"
#include "tests/random_dataset.hpp"

using namespace rapid;
using test::rapid_cli;

namespace {

// A short pendulum job: about a second.
const std::string kShort =
    "--scenario pendulum --set steps=1200 --set warmup_steps=200 --set eval_every=400 --set eval_episodes=2 "
    "--set bc_log_every=200 --set batch_size=32 ";

// A pendulum dataset of uniform-random actions, as a behaviour policy would leave it.
Dataset random_pendulum_dataset(int transitions) {
  PendulumEnv env;
  DatasetBuilder builder(env.obs_dim(), env.act_dim());
  Rng rng(9);
  Vec obs(3), next(3), a(1);
  env.reset(1, obs);
  for (int t = 0; t < transitions; ++t) {
    a[0] = static_cast<float>(rng.uniform(-1, 1));
    const StepResult r = env.step(a, next);
    builder.add(obs, a, r.reward, next, r.terminated, r.truncated);
    obs = next;
    if (r.truncated) env.reset(t, obs);
  }
  return builder.finish();
}

nlohmann::json read_record(const std::string& dir) { return nlohmann::json::parse(read_file(dir + "/record.json")); }

// Everything but what legitimately differs between two runs of one job: times and host.
nlohmann::json comparable(nlohmann::json r) {
  r.erase("timing");
  r.erase("provenance");
  return r;
}

}  // namespace

TEST(RapidRun, WritesACompleteRecord) {
  rapid::testing::ScratchDir dir;
  const auto out = rapid_cli("run " + kShort + "--algo ddpg --seed 3 --out " + dir.file("job"));
  ASSERT_EQ(out.exit_code, 0) << out.text;
  const auto r = read_record(dir.file("job"));
  EXPECT_EQ(r["schema"], "rapid.run/1");
  EXPECT_EQ(r["status"], "ok");
  EXPECT_TRUE(r["error"].is_null());
  EXPECT_EQ(r["cell"], nlohmann::json({{"scenario", "pendulum"}, {"dataset", nullptr}, {"algo", "ddpg"}, {"seed", 3}}));
  EXPECT_EQ(r["config"]["steps"], 1200);
  EXPECT_EQ(r["config_hash"].get<std::string>().size(), 16u);
  for (const char* k : {"code_revision", "code_dirty", "sumo_version", "compiler", "host", "cpu", "start_time", "end_time"})
    EXPECT_TRUE(r["provenance"].contains(k)) << k;
  // Evaluations at step 0, near each multiple of eval_every, and at the end.
  ASSERT_GE(r["eval"].size(), 4u);
  EXPECT_EQ(r["eval"].front()["step"], 0);
  EXPECT_EQ(r["eval"].back()["target_step"], 1200);
  EXPECT_FALSE(r["train_episodes"].empty());
  EXPECT_EQ(r["train_episodes"][0]["length"], 200);
  // Without a prior buffer the prior BC loss is null, the online one measured.
  ASSERT_FALSE(r["bc_loss"].empty());
  EXPECT_TRUE(r["bc_loss"][0]["prior"].is_null());
  EXPECT_TRUE(r["bc_loss"][0]["online"].is_number());
  EXPECT_EQ(r["final"]["last_k"], 3);
  EXPECT_FALSE(r["final"].contains("episodes"));  // no final evaluation in this config
  // One update per decision from the end of the warm-up (200): 1,001, as the checkpoint says too.
  EXPECT_EQ(r["updates"], 1001);
  std::int64_t updates = -1;
  Mlp::load(dir.file("job/actor.ckpt"), &updates);
  EXPECT_EQ(updates, 1001);
  // The two forces on the actor, per logging window: the Q term's gradient measured, no imitation.
  ASSERT_EQ(r["gradients"].size(), r["bc_loss"].size());
  EXPECT_GT(r["gradients"][0]["q_online"].get<double>(), 0);
  EXPECT_EQ(r["gradients"][0]["bc_online"], 0.0);
  EXPECT_TRUE(r["gradients"][0]["q_prior"].is_null());
  EXPECT_FALSE(r["losses"][0].contains("temperature")) << "DDPG has no entropy temperature";
  EXPECT_GT(r["timing"]["env_steps_per_s"].get<double>(), 0);
  EXPECT_TRUE(std::filesystem::exists(dir.file("job/actor.ckpt")));
}

TEST(RapidRun, RemovesTheTemporariesAKilledAttemptLeft) {
  rapid::testing::ScratchDir dir;
  std::filesystem::create_directories(dir.file("job"));
  // A killed attempt leaves its lock file (taken before anything else is written) and temporaries.
  write_file_atomic(dir.file("job/.rapid-run.lock"), "4242\n");
  for (const char* f : {"record.json.tmp.4242", "actor.ckpt.tmp.4242", "progress.json.tmp.17", "mine.txt.tmp.5"})
    write_file_atomic(dir.file(std::string("job/") + f), "half");
  const auto out = rapid_cli("run " + kShort + "--algo ddpg --seed 3 --out " + dir.file("job"), /*with_stderr=*/true);
  ASSERT_EQ(out.exit_code, 0) << out.text;
  EXPECT_NE(out.text.find("removed 3 temporary file(s)"), std::string::npos) << out.text;
  for (const char* f : {"record.json.tmp.4242", "actor.ckpt.tmp.4242", "progress.json.tmp.17"})
    EXPECT_FALSE(std::filesystem::exists(dir.file(std::string("job/") + f))) << f;
  EXPECT_TRUE(std::filesystem::exists(dir.file("job/mine.txt.tmp.5")));  // not the job's file
  EXPECT_EQ(read_record(dir.file("job"))["status"], "ok");
}

TEST(RapidRun, SameSeedGivesTheSameRecord) {
  rapid::testing::ScratchDir dir;
  for (const char* job : {"a", "b"})
    ASSERT_EQ(rapid_cli("run " + kShort + "--algo ddpg --seed 5 --out " + dir.file(job)).exit_code, 0);
  EXPECT_EQ(comparable(read_record(dir.file("a"))), comparable(read_record(dir.file("b"))));
  ASSERT_EQ(rapid_cli("run " + kShort + "--algo ddpg --seed 6 --out " + dir.file("c")).exit_code, 0);
  EXPECT_NE(read_record(dir.file("a"))["eval"], read_record(dir.file("c"))["eval"]);
}

TEST(RapidRun, PriorAlgorithmReadsADatasetAndLogsBothBcLosses) {
  rapid::testing::ScratchDir dir;
  write_dataset(dir.file("prior.h5"), random_pendulum_dataset(600));
  const auto out = rapid_cli("run " + kShort + "--algo rapid-rl --dataset " + dir.file("prior.h5") +
                             " --seed 1 --out " + dir.file("job"), /*with_stderr=*/true);
  ASSERT_EQ(out.exit_code, 0) << out.text;
  const auto r = read_record(dir.file("job"));
  EXPECT_EQ(r["cell"]["dataset"], dir.file("prior.h5"));
  EXPECT_TRUE(r["bc_loss"][0]["prior"].is_number());
  EXPECT_TRUE(r["bc_loss"][0]["online"].is_number());
  for (const char* k : {"q_prior", "q_online", "bc_prior", "bc_online"})
    EXPECT_TRUE(r["gradients"][0][k].is_number()) << k;
}

// A config with a final evaluation (the flow profile's) reports its mean as the final return,
// with its episodes, and keeps the last K evaluations' mean beside it.
TEST(RapidRun, AFinalEvaluationIsTheFinalReturn) {
  rapid::testing::ScratchDir dir;
  const auto out = rapid_cli("run " + kShort + "--set final_eval_episodes=6 --algo ddpg --seed 3 --out " + dir.file("job"));
  ASSERT_EQ(out.exit_code, 0) << out.text;
  const auto r = read_record(dir.file("job"));
  const auto& f = r["final"];
  ASSERT_EQ(f["episodes"], 6);
  ASSERT_EQ(f["episode_returns"].size(), 6u);
  double sum = 0;
  for (const auto& x : f["episode_returns"]) sum += x.get<double>();
  EXPECT_NEAR(f["return_mean"].get<double>(), sum / 6, 1e-9);
  EXPECT_EQ(f["last_k"], 3);
  EXPECT_TRUE(f["last_k_mean"].is_number());
  // The curve's last point is the final evaluation's first two episodes.
  EXPECT_NEAR(r["eval"].back()["return_mean"].get<double>(),
              (f["episode_returns"][0].get<double>() + f["episode_returns"][1].get<double>()) / 2, 1e-9);
}

// RAPID-RL (return) trains like RAPID-RL once it has its window; it refuses to run without the
// key (no hidden default) and on a dataset with no episode end, as bad input: exit 2, one line,
// nothing written.
TEST(RapidRun, RapidRlReturnNeedsItsWindowAndADatasetOfEpisodes) {
  rapid::testing::ScratchDir dir;
  write_dataset(dir.file("prior.h5"), random_pendulum_dataset(600));
  Dataset unbroken = random_pendulum_dataset(600);
  unbroken.terminals.assign(unbroken.size(), false);
  unbroken.timeouts.assign(unbroken.size(), false);
  write_dataset(dir.file("unbroken.h5"), unbroken);
  const auto run = [&](const std::string& algo, const std::string& file, const std::string& sets, const std::string& out) {
    return rapid_cli("run " + kShort + sets + "--algo " + algo + " --dataset " + dir.file(file) + " --seed 1 --out " +
                         dir.file(out),
                     /*with_stderr=*/true);
  };

  auto r = run("rapid-rl-return", "prior.h5", "", "missing");
  EXPECT_EQ(r.exit_code, 2) << r.text;
  EXPECT_EQ(r.text,
            "rapid: error: algorithm 'rapid-rl-return' needs config key 'return_horizon' (decisions of the return "
            "window; e.g. --set return_horizon=20)\n");
  EXPECT_FALSE(std::filesystem::exists(dir.file("missing")));

  r = run("rapid-rl-return", "unbroken.h5", "--set return_horizon=20 ", "unbroken");
  EXPECT_EQ(r.exit_code, 2) << r.text;
  EXPECT_EQ(r.text, "rapid: error: --dataset: dataset " + dir.file("unbroken.h5") +
                        ": has no episode ends (terminals/timeouts all false); rapid-rl-return needs episodes\n");
  EXPECT_FALSE(std::filesystem::exists(dir.file("unbroken")));

  r = run("rapid-rl-return", "prior.h5", "--set return_horizon=20 ", "job");
  ASSERT_EQ(r.exit_code, 0) << r.text;
  const auto record = read_record(dir.file("job"));
  EXPECT_EQ(record["status"], "ok");
  EXPECT_EQ(record["config"]["return_horizon"], 20);
  EXPECT_FALSE(record["config"].contains("bc_q_alpha")) << "an optional key left out stays out";
  // RAPID-RL needs no episodes: the same unbroken file is fine for it.
  EXPECT_EQ(run("rapid-rl", "unbroken.h5", "", "rapid-rl").exit_code, 0);
}

TEST(RapidRun, DivergenceIsRecordedNotCrashed) {
  rapid::testing::ScratchDir dir;
  const auto out = rapid_cli("run " + kShort + "--algo ddpg --seed 0 --set critic_lr=1e30 --set actor_lr=1e30 --out " +
                             dir.file("job"));
  EXPECT_EQ(out.exit_code, 1);
  const auto r = read_record(dir.file("job"));
  EXPECT_EQ(r["status"], "diverged");
  EXPECT_NE(r["error"].get<std::string>().find("diverged at step"), std::string::npos);
  EXPECT_FALSE(r["eval"].empty()) << "curves measured before the divergence are kept";
}

TEST(RapidRun, BadInputExitsTwoWithOneLineAndWritesNothing) {
  rapid::testing::ScratchDir dir;
  write_dataset(dir.file("wrong_dims.h5"), rapid::testing::make_dataset(5, 2, {50}));
  const std::string out = " --out " + dir.file("job");
  const std::pair<std::string, std::string> cases[] = {
      {"run --scenario pendulum --algo sac --seed 0" + out, "--algo: unknown algorithm 'sac'"},
      {"run --scenario highway --algo ddpg --seed 0" + out, "--scenario: unknown scenario 'highway'"},
      {"run --scenario pendulum --algo ddpg --seed -1" + out, "--seed: must be a non-negative integer"},
      {"run --scenario pendulum --algo ddpg --seed 0 --set stepz=3" + out, "unknown config key 'stepz'"},
      {"run --scenario pendulum --algo ddpg --seed 0 --set steps=abc" + out, "config key 'steps' expects an integer"},
      {"run --scenario pendulum --algo ddpg --seed 0 --set batch_size=1" + out, "'batch_size' must be at least 2"},
      {"run --scenario pendulum --algo ddpg --seed 0 --dataset medium" + out, "'ddpg' takes no dataset"},
      {"run --scenario pendulum --algo rlpd --seed 0" + out, "'rlpd' needs a prior dataset"},
      {"run --scenario pendulum --algo rlpd --seed 0 --dataset-dir " + dir.file("none") + " --dataset medium" + out,
       "no dataset file at"},
  };
  for (const auto& [args, message] : cases) {
    const auto r = rapid_cli(args, /*with_stderr=*/true);
    EXPECT_EQ(r.exit_code, 2) << args;
    EXPECT_NE(r.text.find(message), std::string::npos) << args << "\n" << r.text;
    EXPECT_EQ(std::count(r.text.begin(), r.text.end(), '\n'), 1) << args << "\n" << r.text;
    EXPECT_FALSE(std::filesystem::exists(dir.file("job"))) << args;
  }
  // A dataset that does not fit the scenario is bad input too: refused before anything is
  // written, not a failed run with a record (tests/datasets/test_dataset_cli.cpp has every kind).
  write_dataset(dir.file("wide.h5"), rapid::testing::make_dataset(3, 1, {50}));
  const std::pair<std::string, std::string> datasets[] = {{"wrong_dims.h5", "'observations' has 5 columns"},
                                                          {"wide.h5", "actions must lie in [-1, 1]"}};
  for (const auto& [file, message] : datasets) {
    const auto r = rapid_cli("run --scenario pendulum --algo rlpd --seed 0 --dataset " + dir.file(file) + out, true);
    EXPECT_EQ(r.exit_code, 2) << file;
    EXPECT_NE(r.text.find("rapid: error: --dataset: dataset " + dir.file(file) + ": " + message), std::string::npos) << r.text;
    EXPECT_EQ(std::count(r.text.begin(), r.text.end(), '\n'), 1) << r.text;
    EXPECT_FALSE(std::filesystem::exists(dir.file("job"))) << file;
  }
}

// `rapid run` resolves its config once: the profile's file, the grid, --set and the recipe merge as
// JSON, and one parse makes the typed config the run uses (run_job takes it from the job spec).
TEST(RapidRun, ParsesItsConfigOnce) {
  rapid::testing::ScratchDir dir;
  CLI::App app;
  const Command run = add_run_command(app);
  app.parse("run --algo ddpg --seed 3 " + kShort + "--out " + dir.file("job"), /*program_name_included=*/false);
  const long before = run_config_parses();
  ASSERT_EQ(run.run(), 0);
  EXPECT_EQ(run_config_parses() - before, 1);
  EXPECT_EQ(read_record(dir.file("job"))["status"], "ok");
}

// --print-config shows every key the run reads with its value and the layer it came from, and
// runs nothing.
TEST(RapidRun, PrintConfigNamesWhereEachKeyCameFrom) {
  rapid::testing::ScratchDir dir;
  const std::string grid = dir.file("g.json");
  write_file_atomic(grid, R"({"name": "g", "scenarios": ["pendulum"], "datasets": ["medium"], "algos": ["rlpd-sac"],
                      "seeds": [0], "algo_config": {"pendulum": {"rlpd-sac": {"critic_subset": 3}}}})");
  write_dataset(dir.file("d.h5"), random_pendulum_dataset(300));
  const auto r = rapid_cli("run --scenario pendulum --algo rlpd-sac --seed 0 --dataset " + dir.file("d.h5") + " --grid " + grid +
                               " --set steps=500 --print-config --out " + dir.file("job"),
                           /*with_stderr=*/true);
  EXPECT_EQ(r.exit_code, 0) << r.text;
  const auto line_of = [&](const std::string& key) {
    const auto at = r.text.find("\n" + key + " ");
    return at == std::string::npos ? std::string() : r.text.substr(at + 1, r.text.find('\n', at + 1) - at - 1);
  };
  EXPECT_NE(line_of("steps").find("500  "), std::string::npos) << r.text;
  EXPECT_TRUE(line_of("steps").ends_with("--set")) << r.text;
  EXPECT_TRUE(line_of("critic_subset").ends_with("grid")) << r.text;
  EXPECT_TRUE(line_of("utd_ratio").ends_with("recipe of rlpd-sac")) << r.text;
  EXPECT_TRUE(line_of("actor_lr").ends_with("experiments/configs/short/pendulum.json")) << r.text;
  EXPECT_EQ(line_of("epsilon"), "") << "rlpd-sac does not read ε: " << r.text;
  EXPECT_EQ(line_of("policy_delay"), "") << "nor td3-bc's delay";
  EXPECT_FALSE(std::filesystem::exists(dir.file("job")));
}

// Issue #67: --print-config runs nothing, so it needs no --out, no --seed and no dataset; a run
// still needs all three, with CLI11's words.
TEST(RapidRun, PrintConfigNeedsNothingARunNeeds) {
  const auto shown = rapid_cli("run --scenario merge --algo rapid-rl --print-config", /*with_stderr=*/true);
  EXPECT_EQ(shown.exit_code, 0) << shown.text;
  EXPECT_NE(shown.text.find("\nepsilon "), std::string::npos) << shown.text;
  const std::pair<std::string, std::string> runs[] = {
      {"run --scenario merge --algo ddpg --seed 1", "rapid: error: --out is required\n"},
      {"run --scenario merge --algo ddpg --out /nonexistent/job", "rapid: error: --seed is required\n"},
      {"run --scenario merge --algo rapid-rl --seed 0 --out /nonexistent/job",
       "rapid: error: --dataset: algorithm 'rapid-rl' needs a prior dataset"}};
  for (const auto& [command, message] : runs) {
    const auto r = rapid_cli(command, /*with_stderr=*/true);
    EXPECT_EQ(r.exit_code, 2) << command << "\n" << r.text;
    EXPECT_EQ(r.text.rfind(message, 0), 0u) << command << "\n" << r.text;
  }
}

// --out must be a folder rapid can write: otherwise exit 2 naming the option, before any work.
TEST(RapidRun, AnUnusableOutFolderIsBadInput) {
  rapid::testing::ScratchDir dir;
  write_file_atomic(dir.file("a_file"), "mine");
  const std::pair<std::string, std::string> cases[] = {
      {"''", "--out: must name a folder, got an empty path"},
      {dir.file("a_file"), "--out: '" + dir.file("a_file") + "' is not a folder"},
      {dir.file("a_file") + "/job", "--out: cannot "},
      {dir.file(std::string(300, 'x')), "--out: cannot "},
  };
  for (const auto& [out, message] : cases) {
    const auto r = rapid_cli("run " + kShort + "--algo ddpg --seed 0 --out " + out, /*with_stderr=*/true);
    EXPECT_EQ(r.exit_code, 2) << out << "\n" << r.text;
    EXPECT_NE(r.text.find("rapid: error: " + message), std::string::npos) << out << "\n" << r.text;
    EXPECT_EQ(std::count(r.text.begin(), r.text.end(), '\n'), 1) << r.text;
  }
  EXPECT_EQ(read_file(dir.file("a_file")), "mine");
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()), {}), 1) << "nothing else was written";
}

// `rapid run --out` follows the folder rules of `rapid sweep`: a folder of the user's own is
// refused (a record.json counts as rapid's only when it is a run record), a folder a run wrote
// before is rerun into, and --force writes into any folder.
TEST(RapidRun, AFolderOfTheUsersOwnIsRefusedUnlessForced) {
  rapid::testing::ScratchDir dir;
  const auto run = [&](const std::string& folder, const std::string& extra = "") {
    return rapid_cli("run " + kShort + "--algo ddpg --seed 0 --out " + dir.file(folder) + extra, /*with_stderr=*/true);
  };
  std::filesystem::create_directories(dir.file("notes"));
  write_file_atomic(dir.file("notes/todo.txt"), "mine");
  std::filesystem::create_directories(dir.file("records"));
  write_file_atomic(dir.file("records/record.json"), "my own record");
  std::filesystem::create_directories(dir.file("json"));
  write_file_atomic(dir.file("json/record.json"), R"({"schema": "mine/1", "status": "ok"})");
  for (const std::string folder : {"notes", "records", "json"}) {
    const auto before = std::distance(std::filesystem::directory_iterator(dir.file(folder)), {});
    const auto r = run(folder);
    EXPECT_EQ(r.exit_code, 2) << folder << "\n" << r.text;
    EXPECT_EQ(r.text, "rapid: error: --out: '" + dir.file(folder) +
                          "' holds files but is not a run folder; name a new or empty folder, or add --force to "
                          "write into it anyway\n")
        << folder;
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.file(folder)), {}), before) << "nothing written";
  }
  EXPECT_EQ(read_file(dir.file("records/record.json")), "my own record");
  EXPECT_EQ(read_file(dir.file("json/record.json")), R"({"schema": "mine/1", "status": "ok"})");

  // A rerun into a folder that holds a run record goes ahead, as does --force.
  ASSERT_EQ(run("job").exit_code, 0);
  write_file_atomic(dir.file("job/notes.txt"), "mine too");
  const auto again = run("job");
  EXPECT_EQ(again.exit_code, 0) << again.text;
  const auto forced = run("records", " --force");
  EXPECT_EQ(forced.exit_code, 0) << forced.text;
  EXPECT_EQ(read_record(dir.file("records"))["schema"], "rapid.run/1");
}

// Two runs into one folder at once: the second is refused naming the first, instead of
// overwriting its files.
TEST(RapidRun, ASecondRunIntoAFolderInUseIsRefused) {
  rapid::testing::ScratchDir dir;
  const std::string job = dir.file("job");
  const pid_t first = ::fork();
  ASSERT_GE(first, 0);
  if (first == 0) {
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, 1);
    ::dup2(null, 2);
    ::execl(RAPID_BIN, RAPID_BIN, "run", "--scenario", "pendulum", "--algo", "ddpg", "--seed", "0", "--set",
            "steps=1000000", "--out", job.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!std::filesystem::exists(job + "/progress.json") && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  const bool started = std::filesystem::exists(job + "/progress.json");
  const auto second = started ? rapid_cli("run " + kShort + "--algo ddpg --seed 1 --out " + job, /*with_stderr=*/true)
                              : test::CliOutput{};
  ::kill(first, SIGKILL);
  ::waitpid(first, nullptr, 0);
  ASSERT_TRUE(started) << "the first run did not start";
  EXPECT_EQ(second.exit_code, 2) << second.text;
  EXPECT_EQ(second.text, "rapid: error: --out: run folder " + job + " is in use by another rapid run (pid " +
                             std::to_string(first) + ")\n");
  EXPECT_FALSE(std::filesystem::exists(job + "/record.json")) << "the second run wrote nothing";
}

// DDPG learns the swing-up: ≥ −200 final mean evaluation return within 20,000 steps (a
// well-tuned DDPG scores about −150). One seed keeps this a few seconds; the README's
// "Algorithm check" runs all five.
TEST(RapidRun, DdpgLearnsPendulum) {
  rapid::testing::ScratchDir dir;
  ASSERT_EQ(rapid_cli("run --scenario pendulum --algo ddpg --seed 1 --out " + dir.file("job")).exit_code, 0);
  const auto r = read_record(dir.file("job"));
  EXPECT_EQ(r["config"]["steps"], 20000);
  EXPECT_LT(r["eval"][0]["return_mean"].get<double>(), -800.0) << "the untrained policy is poor";
  EXPECT_GE(r["final"]["return_mean"].get<double>(), -200.0);
}

// What the published RLPD (SAC, 10 critics, UTD 20) and TD3+BC are expected to reach on the
// swing-up from each prior dataset, and why: half of every batch from a pendulum dataset of a DDPG
// reference of 4,000 decisions (`medium`: its T/2 actor, episode returns about −1,200, no swing-up
// in the data; `final`: its last actor, swinging up: about −180 since the exact-sqrt build of
// 2026-12-02, −490 before), 20,000 decisions, seeds no other test uses. Published references:
// SAC and TD3 on Pendulum-v1 reach about −150 at 20,000 steps (rl-baselines3-zoo's benchmark),
// and RLPD learns from data of any quality because nothing in its loss ties the policy to the
// data (Ball et al. 2023, §5): so rlpd-sac reaches −200 from `medium`. TD3+BC's imitation term
// at α = 2.5 holds the policy near the data's actions (Fujimoto & Gu 2021, Table 1: on the
// `random` datasets, whose behaviour never solves a task, TD3+BC scores near that behaviour):
// from `medium` it stays near the data, below −600. That case is the method's limit, kept here as
// documented behaviour: with the backbone's LayerNorm critic (before #41) it still reached −254
// from `medium`; TD3_BC's own critic has no LayerNorm, and with it the Q term never outweighs the
// imitation. From `final`, whose actions swing up, it swings up too, above −300: not always to
// −200, since of 22 runs (seeds 72 and 80-89, on the datasets of the builds before and after
// 2026-12-02) all ended at −137 to −158 but three of the later build's, at −265 to −279 (a
// swing-up missed from a few starts). rlpd-sac takes a few minutes: twenty ensemble steps per
// decision. The Q-filter (Nair et al. 2018, §IV-C) drops the imitation of every prior action the
// critic rates below the actor's, so that the policy can surpass poor demonstrations: from
// `medium` it reaches −200 (expected before it was first run; it measured −136 on seed 73,
// CoL-prior −145 there: the swing-up is easy enough that this checks learning, not the filter,
// which QFilter in tests/test_algos.cpp checks).
struct PendulumCase {
  const char* algo;
  const char* dataset;
  int seed;
  bool swings_up;  // final return ≥ swing_up_line; otherwise held near the data: below −600
  double swing_up_line = -200.0;
};

// A failing case names itself in GoogleTest's output instead of printing its bytes.
void PrintTo(const PendulumCase& c, std::ostream* os) {
  *os << c.algo << " on " << c.dataset << ", seed " << c.seed;
}

class PublishedBaselineOnPendulum : public ::testing::TestWithParam<PendulumCase> {};

TEST_P(PublishedBaselineOnPendulum, ReachesWhatTheMethodReachesFromItsData) {
  const auto [algo, dataset, seed, swings_up, swing_up_line] = GetParam();
  ::setenv("OMP_NUM_THREADS", "1", 1);  // CTest runs tests side by side
  rapid::testing::ScratchDir dir;
  ASSERT_EQ(rapid_cli("dataset build --scenario pendulum --dir " + dir.file("d") +
                      " --set steps=4000 --set warmup_steps=0").exit_code, 0);
  ASSERT_EQ(rapid_cli(std::string("run --scenario pendulum --algo ") + algo + " --dataset " + dataset + " --dataset-dir " +
                      dir.file("d") + " --seed " + std::to_string(seed) + " --out " + dir.file("job")).exit_code, 0);
  const auto r = read_record(dir.file("job"));
  EXPECT_EQ(r["config"]["steps"], 20000);
  EXPECT_EQ(r.contains("recipe"), !find_algorithm(algo).recipe.empty()) << "a published recipe's keys were filled";
  EXPECT_LT(r["eval"][0]["return_mean"].get<double>(), -800.0) << "the untrained policy is poor";
  const double final_return = r["final"]["return_mean"].get<double>();
  if (swings_up) EXPECT_GE(final_return, swing_up_line) << algo << " on " << dataset;
  else EXPECT_LT(final_return, -600.0) << algo << " on " << dataset << " was expected to stay near its data";
}

INSTANTIATE_TEST_SUITE_P(RapidRun, PublishedBaselineOnPendulum,
                         ::testing::Values(PendulumCase{"rlpd-sac", "medium", 71, true},
                                           PendulumCase{"td3-bc", "final", 72, true, -300.0},
                                           PendulumCase{"td3-bc", "medium", 72, false},
                                           PendulumCase{"q-filter", "medium", 73, true}),
                         [](const auto& info) {
                           std::string name = std::string(info.param.algo) + "_" + info.param.dataset;
                           for (char& c : name)
                             if (c == '-' || c == '+') c = '_';
                           return name;
                         });

// rlpd-sac and td3-bc run on every driving scenario through the same command as the paper's five,
// with their recipes filled in and recorded (a short run on a random dataset of the scenario).
TEST(RapidRun, ThePublishedBaselinesRunOnEveryDrivingScenario) {
  ::setenv("OMP_NUM_THREADS", "1", 1);
  rapid::testing::ScratchDir dir;
  for (const std::string scenario : {"lane-drop", "cut-in", "merge"}) {
    const std::string data = dir.file(scenario + ".h5");
    write_dataset(data, test::random_dataset(scenario, 200));
    for (const std::string algo : {"rlpd-sac", "td3-bc"}) {
      const std::string job = dir.file(scenario + "-" + algo);
      const auto out = rapid_cli("run --scenario " + scenario + " --algo " + algo + " --dataset " + data +
                                     " --set steps=60 --set warmup_steps=0 --set eval_every=60 --set eval_episodes=1"
                                     " --set bc_log_every=30 --set batch_size=16 --seed 1 --out " + job,
                                 /*with_stderr=*/true);
      ASSERT_EQ(out.exit_code, 0) << scenario << " " << algo << ": " << out.text;
      const auto r = read_record(job);
      EXPECT_EQ(r["status"], "ok") << scenario << " " << algo;
      EXPECT_EQ(r["recipe"]["critic_ensemble"], algo == "rlpd-sac" ? 10 : 2) << scenario << " " << algo;
      // Each code base's own values (docs/algorithms.md, "Which values are the method's").
      EXPECT_EQ(r["recipe"]["critic_layer_norm"], algo == "rlpd-sac") << scenario << " " << algo;
      EXPECT_EQ(r["recipe"]["init"], algo == "rlpd-sac" ? "xavier" : "pytorch") << scenario << " " << algo;
      if (algo == "rlpd-sac") EXPECT_EQ(r["recipe"]["temperature_lr"], 3e-4) << scenario;
      EXPECT_GT(r["updates"].get<long>(), 0) << scenario << " " << algo;
      EXPECT_TRUE(r["final"]["return_mean"].is_number()) << scenario << " " << algo;
      // rlpd-sac logs its learned temperature, which has moved from its initial 1.0; td3-bc has none.
      ASSERT_FALSE(r["losses"].empty()) << scenario << " " << algo;
      for (const auto& point : r["losses"]) {
        if (algo == "td3-bc") {
          EXPECT_FALSE(point.contains("temperature")) << scenario;
          continue;
        }
        ASSERT_TRUE(point.contains("temperature")) << scenario;
        EXPECT_GT(point["temperature"].get<double>(), 0.0) << scenario;
        EXPECT_NE(point["temperature"].get<double>(), 1.0) << scenario;
      }
    }
  }
}

// Bad input outside any subcommand's own checks: still one short line naming what is wrong. An
// unknown subcommand's line lists every subcommand, so it grows with them: it is checked for the
// names rather than for its length.
TEST(RapidCli, AnUnknownSubcommandAndAnOutOfRangeCountAreNamed) {
  const std::pair<std::string, std::string> cases[] = {
      {"frobnicate", "rapid: error: unknown subcommand 'frobnicate'; expected one of rollout, "},
      {"dataset info --bins -1 x.h5", "rapid: error: --bins: must be an integer of at least 1, got '-1'"},
      {"rollout --scenario pendulum --policy zero --seed 0 --episodes 0",
       "rapid: error: --episodes: must be an integer of at least 1, got '0'"},
  };
  for (const auto& [args, message] : cases) {
    const auto r = rapid_cli(args, /*with_stderr=*/true);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.text;
    EXPECT_EQ(r.text.rfind(message, 0), 0u) << args << "\n" << r.text;
    EXPECT_EQ(std::count(r.text.begin(), r.text.end(), '\n'), 1) << r.text;
    if (args != "frobnicate") EXPECT_LT(r.text.size(), 200u) << r.text;
  }
  const std::string unknown = rapid_cli("frobnicate", /*with_stderr=*/true).text;
  const std::string marker = "expected one of ";
  ASSERT_NE(unknown.find(marker), std::string::npos) << unknown;
  std::vector<std::string> names;
  std::stringstream list(unknown.substr(unknown.find(marker) + marker.size()));
  for (std::string name; std::getline(list, name, ',');) {
    name.erase(0, name.find_first_not_of(' '));
    if (!name.empty() && name.back() == '\n') name.pop_back();
    names.push_back(name);
  }
  EXPECT_EQ(names, (std::vector<std::string>{"rollout", "dataset", "run", "sweep", "status", "summarize", "diff", "bench",
                                             "budget", "recheck", "simulate-decide", "replay-decide", "eval-budget", "paper",
                                             "beside", "tune", "rerun"}))
      << unknown;
}

// A sweep's prior dataset exported as a Minari dataset and imported back is the same file, byte
// for byte, so a run on it is the same run: the same config hash, the same record (issue #70).
TEST(RapidRun, AMinariRoundTripGivesTheSameRecord) {
  rapid::testing::ScratchDir dir;
  std::filesystem::create_directories(dir.file("sweep/datasets/pendulum"));
  write_file_atomic(dir.file("sweep/grid.json"),
                    R"({"name": "g", "scenarios": ["pendulum"], "datasets": ["medium"], "algos": ["rapid-rl"], "seeds": [0]})");
  const std::string original = dir.file("sweep/datasets/pendulum/medium.h5");
  write_dataset(original, random_pendulum_dataset(600));
  const auto exported = rapid_cli("dataset export " + dir.file("sweep") + " --format minari --out " + dir.file("root"), true);
  ASSERT_EQ(exported.exit_code, 0) << exported.text;
  EXPECT_NE(exported.text.find("rapid/pendulum-short/medium-v0  3 episodes, 600 steps"), std::string::npos) << exported.text;
  const auto imported =
      rapid_cli("dataset import " + dir.file("root/rapid/pendulum-short/medium-v0") + " --out " + dir.file("back.h5"), true);
  ASSERT_EQ(imported.exit_code, 0) << imported.text;
  EXPECT_EQ(read_file(dir.file("back.h5")), read_file(original));

  for (const auto& [job, file] : {std::pair{"a", original}, std::pair{"b", dir.file("back.h5")}})
    ASSERT_EQ(rapid_cli("run " + kShort + "--algo rapid-rl --dataset " + file + " --seed 1 --out " + dir.file(job)).exit_code, 0);
  nlohmann::json a = comparable(read_record(dir.file("a"))), b = comparable(read_record(dir.file("b")));
  EXPECT_EQ(a["config_hash"], b["config_hash"]);
  for (nlohmann::json* r : {&a, &b}) r->erase("dataset_file"), (*r)["cell"].erase("dataset");  // the paths differ
  EXPECT_EQ(a, b) << nlohmann::json::diff(a, b).dump();

  // Exporting again over what is there writes nothing and says why.
  const auto again = rapid_cli("dataset export " + dir.file("sweep") + " --out " + dir.file("root"), true);
  EXPECT_EQ(again.exit_code, 2);
  EXPECT_NE(again.text.find("medium-v0/data already exists"), std::string::npos) << again.text;
  const auto over = rapid_cli("dataset import " + dir.file("root/rapid/pendulum-short/medium-v0") + " --out " + original, true);
  EXPECT_EQ(over.exit_code, 2);
  EXPECT_NE(over.text.find("already exists (--force replaces it)"), std::string::npos) << over.text;
  const auto not_minari = rapid_cli("dataset import " + dir.file("sweep") + " --out " + dir.file("x.h5"), true);
  EXPECT_EQ(not_minari.exit_code, 2);
  EXPECT_NE(not_minari.text.find("is not a Minari dataset folder"), std::string::npos) << not_minari.text;
  EXPECT_FALSE(std::filesystem::exists(dir.file("x.h5")));
}
