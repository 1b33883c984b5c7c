// The array task, run by hand the way Slurm runs it (`rapid sweep SWEEP --run-job I --job-list
// LIST`): it keeps the local pool's bookkeeping (log header per attempt, retries, outcome.json),
// so `rapid status` shows its result and the next submission includes exactly what failed; it
// refuses to run before its dependencies are done; bad arguments are usage errors.
#include <gtest/gtest.h>

#include <fstream>

#include "tests/datasets/dataset_fixtures.hpp"
#include "tests/slurm/slurm_test_util.hpp"
#include "tests/sweep/sweep_test_util.hpp"

namespace rapid {
namespace {

using namespace sweep_test;
using slurm_test::FakeSlurm;
using nlohmann::json;

class SlurmTask : public ::testing::Test {
 protected:
  void SetUp() override {
    grid_ = pendulum_grid("tasks", {"rapid-rl", "ddpg"}, {0}, 400);
    grid_["max_retries"] = 1;
    write_json(grid_path_, grid_);
  }
  // Submits to the fake sbatch; returns the task list of the cells-pendulum array (the cells that
  // need the datasets, or all cells once the datasets are there).
  std::string submit() {
    const Result r = run_rapid("sweep " + grid_path_.string() + " --backend slurm --out " + sweep_.string());
    EXPECT_EQ(r.exit_code, 0) << r.output;
    const json submissions = read_json(sweep_ / "slurm/submissions.json");
    for (const json& a : submissions["submissions"].back()["arrays"])
      if (a["name"] == "cells-pendulum") return a["list"];
    ADD_FAILURE() << "no cells-pendulum array in " << r.output;
    return "";
  }
  Result task(const std::string& list, int index) {
    return run_rapid("sweep " + sweep_.string() + " --run-job " + std::to_string(index) + " --job-list " + list);
  }
  json status() {
    const Result r = run_rapid("status --json " + sweep_.string());
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return json::parse(r.output);
  }
  std::string log_of(const std::string& job_dir) {
    std::ifstream in(sweep_ / job_dir / "log.txt");
    return std::string(std::istreambuf_iterator<char>(in), {});
  }

  testing::ScratchDir dir_;
  fs::path grid_path_ = dir_.path() / "tasks.json";
  fs::path sweep_ = dir_.path() / "sweep";
  FakeSlurm fake_{dir_.path() / "bin"};
  json grid_;
};

TEST_F(SlurmTask, RunsItsJobWithTheLocalBookkeeping) {
  provide_datasets(sweep_, grid_path_);
  const std::string cells = submit();
  const Result r = task(cells, 1);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("rapid sweep task: ok pendulum/none/ddpg/seed0"), std::string::npos) << r.output;
  const json outcome = read_json(sweep_ / "jobs/pendulum/none/ddpg/seed0/outcome.json");
  EXPECT_EQ(outcome["state"], "ok");
  EXPECT_EQ(outcome["attempts"], 1);
  EXPECT_EQ(log_of("jobs/pendulum/none/ddpg/seed0").rfind("==== rapid sweep: pendulum/none/ddpg/seed0, attempt 1, ", 0), 0u);
  json s = status();
  EXPECT_EQ(s["counts"]["ok"], 3);  // the dataset stage and the ddpg cell
  EXPECT_EQ(s["counts"]["pending"], 1);

  // A task whose job got done meanwhile (a duplicate submission) does nothing.
  const auto before = record_identities(sweep_);
  const Result again = task(cells, 1);
  EXPECT_EQ(again.exit_code, 0) << again.output;
  EXPECT_NE(again.output.find("pendulum/none/ddpg/seed0 is already done"), std::string::npos) << again.output;
  EXPECT_EQ(record_identities(sweep_), before);
}

TEST_F(SlurmTask, AFailedJobIsRetriedRecordedShownByStatusAndResubmitted) {
  provide_datasets(sweep_, grid_path_);
  // A job that fails as it ends (exit 1): its record cannot be written, since record.json is a
  // folder. (A broken dataset would not do: `rapid run` refuses it as bad input, which is not
  // retried.)
  fs::create_directories(sweep_ / "jobs/pendulum/initial/rapid-rl/seed0/record.json/in-the-way");
  const std::string cells = submit();
  const Result r = task(cells, 0);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("rapid sweep task: failed pendulum/initial/rapid-rl/seed0 after 2 attempts: "), std::string::npos)
      << r.output;
  const json outcome = read_json(sweep_ / "jobs/pendulum/initial/rapid-rl/seed0/outcome.json");
  EXPECT_EQ(outcome["state"], "failed");
  EXPECT_EQ(outcome["attempts"], 2) << "retried max_retries times, like the local pool";
  EXPECT_NE(log_of("jobs/pendulum/initial/rapid-rl/seed0").find("attempt 2"), std::string::npos);

  const Result text = run_rapid("status " + sweep_.string());
  EXPECT_NE(text.output.find("  failed    1\n"), std::string::npos) << text.output;
  EXPECT_NE(text.output.find("failed jobs:\n  pendulum/initial/rapid-rl/seed0: failed: "), std::string::npos) << text.output;

  const Result resubmit = run_rapid("sweep " + grid_path_.string() + " --backend slurm --dry-run --out " + sweep_.string());
  EXPECT_NE(resubmit.output.find("#   task 0: pendulum/initial/rapid-rl/seed0\n"), std::string::npos) << resubmit.output;
}

TEST_F(SlurmTask, WaitsForItsDependenciesToBeDone) {
  const std::string cells = submit();  // nothing done: references, datasets and cells arrays
  const Result r = task(cells, 0);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("pendulum/initial/rapid-rl/seed0 needs pendulum/datasets, which is not done"), std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(sweep_ / "jobs/pendulum/initial/rapid-rl/seed0/outcome.json"));
}

TEST_F(SlurmTask, BadArgumentsAreUsageErrors) {
  provide_datasets(sweep_, grid_path_);
  const std::string cells = submit();
  const Result past_end = task(cells, 2);
  EXPECT_EQ(past_end.exit_code, 2) << past_end.output;
  EXPECT_NE(past_end.output.find("index 2 is past the end"), std::string::npos) << past_end.output;
  const Result no_list = run_rapid("sweep " + sweep_.string() + " --run-job 0");
  EXPECT_EQ(no_list.exit_code, 2) << no_list.output;
  const Result missing = task("slurm/nope.json", 0);
  EXPECT_EQ(missing.exit_code, 2) << missing.output;
  EXPECT_NE(missing.output.find("is missing or not a task list"), std::string::npos) << missing.output;
  const Result not_a_sweep = run_rapid("sweep " + dir_.path().string() + " --run-job 0 --job-list " + cells);
  EXPECT_EQ(not_a_sweep.exit_code, 2) << not_a_sweep.output;
}

}  // namespace
}  // namespace rapid
