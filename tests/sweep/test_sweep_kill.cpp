// Reliability under kills (docs/design.md §Sweeps): kill -9 of a training child, kill -9 of the
// runner, a second sweep on a busy folder, and Ctrl-C. Each disturbed sweep must end with the
// same records (timings and provenance times aside) as an undisturbed one.
#include <gtest/gtest.h>
#include <signal.h>

#include <fstream>
#include <sstream>

#include "tests/datasets/dataset_fixtures.hpp"
#include "tests/sweep/sweep_test_util.hpp"

namespace rapid {
namespace {

using namespace sweep_test;
using nlohmann::json;

// Long enough (a couple of seconds per job) to be caught mid-training by its progress file.
constexpr long kSteps = 20000;

class KillSweep : public ::testing::Test {
 protected:
  // Batches of 64: runs slow enough to be caught mid-run (DDPG only, so no dataset constrains it).
  void SetUp() override {
    json grid = pendulum_grid("kill", {"ddpg"}, {0, 1}, kSteps);
    grid["config"]["batch_size"] = 64;
    write_json(grid_path_, grid);
  }

  std::string sweep_args(const fs::path& out, int jobs) const {
    return "sweep " + grid_path_.string() + " --jobs " + std::to_string(jobs) + " --out " + out.string();
  }
  std::map<std::string, json> undisturbed() {
    const fs::path out = dir_.path() / "undisturbed";
    const Result r = run_rapid(sweep_args(out, 2));
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return comparable_records(out);
  }
  std::string log_of(const fs::path& log) const {
    std::ifstream in(log);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }

  testing::ScratchDir dir_;
  fs::path grid_path_ = dir_.path() / "kill.json";
  fs::path sweep_ = dir_.path() / "sweep";
};

TEST_F(KillSweep, AWorkerKilledMidJobIsRetriedAndTheRecordsMatchAnUndisturbedSweep) {
  const fs::path log = dir_.path() / "runner.log";
  const pid_t runner = spawn_rapid(sweep_args(sweep_, 2), log);
  const fs::path progress = sweep_ / "jobs/pendulum/none/ddpg/seed0/progress.json";
  const fs::path record = sweep_ / "jobs/pendulum/none/ddpg/seed0/record.json";
  ASSERT_TRUE(wait_until([&] { return fs::exists(progress) || fs::exists(record); })) << log_of(log);
  const pid_t worker = child_with_argument(runner, "--out jobs/pendulum/none/ddpg/seed0");
  ASSERT_GT(worker, 0);
  ASSERT_FALSE(fs::exists(record)) << "killed too late";
  ASSERT_EQ(::kill(worker, SIGKILL), 0);

  ASSERT_EQ(wait_exit(runner), 0) << log_of(log);
  const json manifest = read_json(sweep_ / "sweep.json");
  EXPECT_EQ(manifest["retries"], 1);
  EXPECT_EQ(manifest["status"], "complete");
  EXPECT_NE(log_of(log).find("killed by SIGKILL"), std::string::npos) << log_of(log);
  EXPECT_EQ(comparable_records(sweep_), undisturbed());
}

TEST_F(KillSweep, AKilledRunnerResumesLeavingFinishedRecordsUntouched) {
  const fs::path log = dir_.path() / "runner.log";
  const pid_t runner = spawn_rapid(sweep_args(sweep_, 1), log);
  // One worker: seed 0 finishes, then seed 1 is caught mid-training.
  const fs::path seed1 = sweep_ / "jobs/pendulum/none/ddpg/seed1";
  ASSERT_TRUE(wait_until([&] { return fs::exists(seed1 / "progress.json") || fs::exists(seed1 / "record.json"); }))
      << log_of(log);
  ASSERT_EQ(::kill(runner, SIGKILL), 0);
  EXPECT_EQ(wait_exit(runner), 128 + SIGKILL);
  ASSERT_TRUE(fs::exists(sweep_ / "jobs/pendulum/none/ddpg/seed0/record.json"));
  ASSERT_FALSE(fs::exists(sweep_ / "jobs/pendulum/none/ddpg/seed1/record.json")) << "killed too late";
  // The training child dies with its runner instead of writing on into the folder.
  EXPECT_TRUE(wait_until([&] { return !process_running_in(sweep_); }, 10));
  const auto finished = record_identities(sweep_);

  const Result rerun = run_rapid(sweep_args(sweep_, 1));
  ASSERT_EQ(rerun.exit_code, 0) << rerun.output;
  EXPECT_EQ(jobs_ran(sweep_), (std::vector<std::string>{"pendulum/none/ddpg/seed1"}));
  EXPECT_EQ(record_identities(sweep_).at("jobs/pendulum/none/ddpg/seed0"), finished.at("jobs/pendulum/none/ddpg/seed0"));
  EXPECT_EQ(comparable_records(sweep_), undisturbed());
}

TEST_F(KillSweep, AJobOverTheTimeoutIsStoppedRetriedAndReportedFailed) {
  // Tens of seconds of training against a one-second limit; max_retries 1.
  json grid = pendulum_grid("timeout", {"ddpg"}, {0}, 10 * kSteps);
  grid["max_retries"] = 1;
  write_json(grid_path_, grid);
  const Result r = run_rapid(sweep_args(sweep_, 1) + " --job-timeout 1s --no-summary");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("timeout  pendulum/none/ddpg/seed0 after 1.0s: stopping it"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("failed pendulum/none/ddpg/seed0: timed out after 1.0s (--job-timeout)"), std::string::npos)
      << r.output;
  const json manifest = read_json(sweep_ / "sweep.json");
  EXPECT_EQ(manifest["retries"], 1);
  EXPECT_FALSE(fs::exists(sweep_ / "jobs/pendulum/none/ddpg/seed0/record.json"));
  EXPECT_FALSE(process_running_in(sweep_));
  const json status = json::parse(run_rapid("status --json " + sweep_.string()).output);
  EXPECT_EQ(status["counts"]["failed"], 1) << status.dump();
}

TEST_F(KillSweep, ASecondSweepOnTheFolderIsRefusedAndCtrlCStopsCleanly) {
  const fs::path log = dir_.path() / "runner.log";
  const pid_t runner = spawn_rapid(sweep_args(sweep_, 2), log);
  const fs::path progress = sweep_ / "jobs/pendulum/none/ddpg/seed0/progress.json";
  ASSERT_TRUE(wait_until([&] { return fs::exists(progress) || fs::exists(sweep_ / "sweep.json"); })) << log_of(log);
  ASSERT_FALSE(fs::exists(sweep_ / "sweep.json")) << "the sweep ended too early";

  const Result second = run_rapid(sweep_args(sweep_, 1));
  EXPECT_EQ(second.exit_code, 2);
  EXPECT_EQ(second.output, "rapid: error: sweep folder " + sweep_.string() + " is in use by another rapid sweep (pid " +
                               std::to_string(runner) + ")\n");
  const Result status = run_rapid("status --json " + sweep_.string());
  ASSERT_EQ(status.exit_code, 0) << status.output;
  EXPECT_EQ(json::parse(status.output)["counts"]["running"], 2) << status.output;

  ASSERT_EQ(::kill(runner, SIGINT), 0);
  EXPECT_EQ(wait_exit(runner), 130) << log_of(log);
  EXPECT_FALSE(process_running_in(sweep_));
  const json manifest = read_json(sweep_ / "sweep.json");
  EXPECT_EQ(manifest["status"], "interrupted");
  EXPECT_EQ(manifest["jobs"]["not_run"], 2);
  EXPECT_FALSE(fs::exists(progress)) << "a stopped job leaves no progress file behind";
  const json after = json::parse(run_rapid("status --json " + sweep_.string()).output);
  EXPECT_EQ(after["counts"]["pending"], 2);
  EXPECT_EQ(after["active"], false);
}

}  // namespace
}  // namespace rapid

namespace rapid {
namespace {

using namespace sweep_test;
using nlohmann::json;

// The end of a sweep (and `rapid summarize`) draws the figures through an interpreter; this one
// stands in for it: it answers "import matplotlib", and as scripts/plot it runs `plot_body`.
class FakePlot : public ::testing::Test {
 protected:
  void SetUp() override {
    write_json(grid_path_, pendulum_grid("reports", {"ddpg"}, {0}, 600));
    const Result done = run_rapid("sweep " + grid_path_.string() + " --jobs 1 --no-summary --out " + sweep_.string());
    ASSERT_EQ(done.exit_code, 0) << done.output;
  }
  void TearDown() override { ::unsetenv("RAPID_PYTHON"); }
  void use_python(const std::string& plot_body) {
    std::ofstream(python_) << "#!/bin/sh\nif [ \"$1\" = -c ]; then exit 0; fi\n" << plot_body << "\n";
    fs::permissions(python_, fs::perms::owner_all);
    ::setenv("RAPID_PYTHON", python_.c_str(), 1);
  }
  pid_t plot_pid() const {
    std::ifstream in(pid_file_);
    pid_t pid = -1;
    in >> pid;
    return pid;
  }

  testing::ScratchDir dir_;
  fs::path grid_path_ = dir_.path() / "reports.json";
  fs::path sweep_ = dir_.path() / "sweep";
  fs::path python_ = dir_.path() / "python";
  fs::path pid_file_ = dir_.path() / "plot.pid";
};

// A stop signal while the reports are drawn: exit 130 (not death by the signal), and the plot
// process is stopped with rapid instead of left running.
TEST_F(FakePlot, ASignalWhileTheFiguresAreDrawnExits130AndStopsThePlot) {
  use_python("echo $$ > " + pid_file_.string() + ".tmp && mv " + pid_file_.string() + ".tmp " + pid_file_.string() +
             "\nexec sleep 600");
  const std::string sweep_args = "sweep " + grid_path_.string() + " --jobs 1 --out " + sweep_.string();
  const std::string summarize_args = "summarize " + sweep_.string();
  for (const auto& [args, sig] : std::vector<std::pair<std::string, int>>{
           {sweep_args, SIGTERM}, {sweep_args, SIGHUP}, {sweep_args, SIGINT}, {summarize_args, SIGTERM}}) {
    fs::remove(pid_file_);
    const fs::path log = dir_.path() / "rapid.log";
    const pid_t rapid = spawn_rapid(args, log);
    ASSERT_TRUE(wait_until([&] { return plot_pid() > 0; })) << args;
    const pid_t plot = plot_pid();
    ASSERT_EQ(::kill(rapid, sig), 0);
    EXPECT_EQ(wait_exit(rapid), 130) << args << " " << sig;
    const bool plot_alive = ::kill(plot, 0) == 0;
    EXPECT_FALSE(plot_alive) << args << " " << sig << ": scripts/plot left running";
    if (plot_alive) ::kill(plot, SIGKILL);
  }
}

// A plot process that dies by a signal is named as such, and the sweep that ran it fails.
TEST_F(FakePlot, AKilledPlotProcessFailsTheSweepAndSaysHow) {
  use_python("kill -9 $$");
  const Result r = run_rapid("sweep " + grid_path_.string() + " --jobs 1 --out " + sweep_.string());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("scripts/plot was killed by SIGKILL"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace rapid
