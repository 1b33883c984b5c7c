// `rapid sweep --backend slurm` without a cluster (docs/cluster.md): --dry-run prints one throttled array
// per scenario and stage chained with afterok (cells that need no dataset in an array of their
// own) and writes nothing; a submission (to a fake sbatch) chains the real ids, records them and writes the task lists; a folder whose arrays are still queued is
// refused; a resubmission holds only the jobs that are not done; bad options are usage errors.
#include <gtest/gtest.h>

#include "tests/datasets/dataset_fixtures.hpp"
#include "tests/slurm/slurm_test_util.hpp"
#include "tests/sweep/sweep_test_util.hpp"

namespace rapid {
namespace {

using namespace sweep_test;
using slurm_test::FakeSlurm;
using slurm_test::submitted_ids;
using nlohmann::json;

std::size_t occurrences(const std::string& text, const std::string& needle) {
  std::size_t n = 0;
  for (auto at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1)) ++n;
  return n;
}

class SlurmSubmit : public ::testing::Test {
 protected:
  void SetUp() override {
    grid_ = pendulum_grid("slurmy", {"rapid-rl", "ddpg"}, {0, 1}, 400);
    grid_["max_retries"] = 1;
    write_json(grid_path_, grid_);
  }
  Result sweep(const std::string& extra = "") {
    return run_rapid("sweep " + grid_path_.string() + " --backend slurm --out " + sweep_.string() + " " + extra);
  }

  testing::ScratchDir dir_;
  fs::path grid_path_ = dir_.path() / "slurmy.json";
  fs::path sweep_ = dir_.path() / "sweep";
  FakeSlurm fake_{dir_.path() / "bin"};
  json grid_;
};

// Axes (docs/sweeps.md §Axes): RAPID-RL's cells run at every ε, DDPG's once; --only by value.
TEST_F(SlurmSubmit, DryRunListsTheAxisJobsOnceEachAndOnlySelectsByValue) {
  grid_["axes"] = {{"epsilon", {-0.5, 0.3}}};
  write_json(grid_path_, grid_);
  const Result r = sweep("--dry-run");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const std::string cell : {"pendulum/initial/rapid-rl/epsilon=-0.5/seed0", "pendulum/initial/rapid-rl/epsilon=-0.5/seed1",
                                 "pendulum/initial/rapid-rl/epsilon=0.3/seed0", "pendulum/initial/rapid-rl/epsilon=0.3/seed1",
                                 "pendulum/none/ddpg/seed0", "pendulum/none/ddpg/seed1"})
    EXPECT_EQ(occurrences(r.output, ": " + cell + "\n"), 1u) << cell << "\n" << r.output;
  EXPECT_EQ(occurrences(r.output, "pendulum/reference\n"), 1u) << r.output;
  const Result only = sweep("--dry-run --only epsilon=0.3,algo=rapid-rl");
  ASSERT_EQ(only.exit_code, 0) << only.output;
  EXPECT_EQ(occurrences(only.output, "epsilon=0.3/seed"), 2u) << only.output;
  EXPECT_EQ(occurrences(only.output, "epsilon=-0.5"), 0u) << only.output;
  EXPECT_FALSE(fs::exists(sweep_)) << "a dry run writes nothing";
}

TEST_F(SlurmSubmit, DryRunPrintsThrottledArraysChainedWithAfterokAndWritesNothing) {
  const Result r = sweep("--dry-run --array-parallelism 3 --partition short --time 0:10:00 --sbatch-arg=--mem=2G");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string& out = r.output;
  EXPECT_EQ(occurrences(out, "#!/bin/bash\n"), 4u) << out;
  EXPECT_EQ(occurrences(out, "#SBATCH --array=0-0%3\n"), 2u) << out;  // the reference agent, the datasets
  EXPECT_EQ(occurrences(out, "#SBATCH --array=0-1%3\n"), 2u) << out;  // two rapid-rl cells, two ddpg cells
  EXPECT_NE(out.find("#SBATCH --dependency=afterok:<job id of the references-pendulum array>\n"), std::string::npos)
      << out;
  EXPECT_NE(out.find("#SBATCH --dependency=afterok:<job id of the datasets-pendulum array>\n"), std::string::npos)
      << out;
  EXPECT_EQ(occurrences(out, "#SBATCH --kill-on-invalid-dep=yes\n"), 2u) << out;  // ddpg waits for nothing
  EXPECT_NE(out.find("#SBATCH --chdir=" + sweep_.string() + "\n"), std::string::npos) << out;
  EXPECT_NE(out.find("#SBATCH --output=" + sweep_.string() + "/slurm/cells-pendulum_%A_%a.out\n"), std::string::npos)
      << out;
  EXPECT_NE(out.find("cells-pendulum-independent: 2 tasks"), std::string::npos) << out;
  EXPECT_NE(out.find("#SBATCH --partition=short\n#SBATCH --time=0:10:00\n"), std::string::npos) << out;
  EXPECT_NE(out.find("#SBATCH --mem=2G\n"), std::string::npos) << out;
  EXPECT_NE(out.find("' sweep . --run-job \"$SLURM_ARRAY_TASK_ID\" --job-list 'slurm/"), std::string::npos) << out;
  EXPECT_NE(out.find("#   task 1: pendulum/none/ddpg/seed1"), std::string::npos) << out;
  EXPECT_FALSE(fs::exists(sweep_)) << "a dry run writes nothing";
  EXPECT_TRUE(fake_.submitted().empty());
}

TEST_F(SlurmSubmit, SubmitsOneArrayPerStageEachAfterTheOneBefore) {
  const Result r = sweep("--array-parallelism 2");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::vector<std::string> ids = {"100", "101", "102", "103"};
  EXPECT_EQ(submitted_ids(r.output), ids) << r.output;
  ASSERT_EQ(fake_.submitted(), ids);
  EXPECT_EQ(fake_.script("100").find("--dependency"), std::string::npos);
  EXPECT_NE(fake_.script("101").find("#SBATCH --dependency=afterok:100\n"), std::string::npos) << fake_.script("101");
  EXPECT_NE(fake_.script("102").find("#SBATCH --dependency=afterok:101\n"), std::string::npos) << fake_.script("102");
  EXPECT_NE(fake_.script("102").find("#SBATCH --array=0-1%2\n"), std::string::npos) << fake_.script("102");
  EXPECT_EQ(fake_.script("103").find("--dependency"), std::string::npos) << fake_.script("103");  // ddpg

  const json submissions = read_json(sweep_ / "slurm/submissions.json");
  ASSERT_EQ(submissions["submissions"].size(), 1u);
  const json& arrays = submissions["submissions"][0]["arrays"];
  ASSERT_EQ(arrays.size(), 4u);
  EXPECT_EQ(arrays[2]["stage"], "cells");
  EXPECT_EQ(arrays[2]["scenario"], "pendulum");
  EXPECT_EQ(arrays[2]["name"], "cells-pendulum");
  EXPECT_EQ(arrays[2]["job_id"], "102");
  EXPECT_EQ(arrays[2]["after"], "101");
  EXPECT_EQ(arrays[2]["tasks"], 2);
  const json cells = read_json(sweep_ / arrays[2]["list"].get<std::string>());
  ASSERT_EQ(cells["jobs"].size(), 2u);
  EXPECT_EQ(cells["jobs"][0]["job"], "pendulum/initial/rapid-rl/seed0");
  EXPECT_EQ(arrays[3]["name"], "cells-pendulum-independent");
  EXPECT_TRUE(arrays[3]["after"].is_null());
  const json independent = read_json(sweep_ / arrays[3]["list"].get<std::string>());
  EXPECT_EQ(independent["jobs"][1]["job"], "pendulum/none/ddpg/seed1");
  EXPECT_TRUE(fs::exists(sweep_ / "grid.json"));
}

TEST_F(SlurmSubmit, RefusesToSubmitWhileEarlierArraysAreQueued) {
  ASSERT_EQ(sweep().exit_code, 0);
  fake_.set_queue({"55", "101"});
  const Result again = sweep();
  EXPECT_EQ(again.exit_code, 2) << again.output;
  EXPECT_NE(again.output.find("still has Slurm jobs queued or running (101)"), std::string::npos) << again.output;
  EXPECT_EQ(fake_.submitted().size(), 4u);

  fake_.set_queue({"55"});  // somebody else's job
  const Result later = sweep();
  EXPECT_EQ(later.exit_code, 0) << later.output;
  EXPECT_EQ(fake_.submitted().size(), 8u) << "nothing ran, so everything is submitted again";
}

TEST_F(SlurmSubmit, ResubmitsOnlyWhatIsNotDone) {
  provide_datasets(sweep_, grid_path_);
  const Result local = run_rapid("sweep " + grid_path_.string() + " --out " + sweep_.string() + " --only algo=ddpg --jobs 2");
  ASSERT_EQ(local.exit_code, 0) << local.output;

  const Result dry = sweep("--dry-run");
  ASSERT_EQ(dry.exit_code, 0) << dry.output;
  EXPECT_EQ(occurrences(dry.output, "#!/bin/bash\n"), 1u) << dry.output;
  EXPECT_NE(dry.output.find("#   task 0: pendulum/initial/rapid-rl/seed0\n#   task 1: pendulum/initial/rapid-rl/seed1\n\n"),
            std::string::npos)
      << dry.output;
  EXPECT_EQ(dry.output.find("ddpg"), std::string::npos) << dry.output;
  EXPECT_EQ(dry.output.find("--dependency"), std::string::npos) << dry.output;

  const Result r = sweep();
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("submitted 2 jobs to Slurm (4 already done)"), std::string::npos) << r.output;
  EXPECT_EQ(submitted_ids(r.output), std::vector<std::string>{"100"});

  // --force with --only resubmits the selected cells even though they are done.
  const Result forced = sweep("--only algo=ddpg,seed=1 --force --dry-run");
  ASSERT_EQ(forced.exit_code, 0) << forced.output;
  EXPECT_NE(forced.output.find("#   task 0: pendulum/none/ddpg/seed1 (forced)\n\n"), std::string::npos) << forced.output;

  // Once everything is done there is nothing to submit.
  ASSERT_EQ(run_rapid("sweep " + grid_path_.string() + " --out " + sweep_.string() + " --jobs 2").exit_code, 0);
  const Result nothing = sweep();
  EXPECT_EQ(nothing.exit_code, 0) << nothing.output;
  EXPECT_NE(nothing.output.find("nothing to submit, all 6 jobs are done"), std::string::npos) << nothing.output;
  EXPECT_EQ(fake_.submitted().size(), 1u);
}

TEST_F(SlurmSubmit, AnSbatchFailureIsReportedAndLeavesNoSubmissionBehind) {
  fake_.fail_submissions(true);
  const Result r = sweep();
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("sbatch failed for the references-pendulum array: sbatch: error: Batch job submission failed: "
                          "Invalid partition name specified"),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(sweep_ / "slurm/submissions.json"));
  EXPECT_TRUE(fs::is_empty(sweep_ / "slurm"));
}

TEST_F(SlurmSubmit, BadOptionsAreUsageErrorsAndWriteNothing) {
  const std::string grid = grid_path_.string(), out = " --out " + sweep_.string();
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"sweep " + grid + out + " --partition short", "need --backend slurm"},
      {"sweep " + grid + out + " --dry-run", "need --backend slurm"},
      {"sweep " + grid + out + " --backend pbs", "expected local or slurm"},
      {"sweep " + grid + out + " --backend slurm --jobs 2", "--array-parallelism"},
      {"sweep " + grid + out + " --backend slurm --sbatch-arg=--array=0-3", "is set by rapid sweep itself"},
      {"sweep " + grid + out + " --backend slurm --sbatch-arg=-o/tmp/x", "is set by rapid sweep itself"},
      {"sweep " + grid + out + " --backend slurm --sbatch-arg=mem", "is not an sbatch option"},
      {"sweep " + grid + out + " --backend slurm --array-parallelism 0", "--array-parallelism"},
  };
  for (const auto& [args, message] : cases) {
    const Result r = run_rapid(args);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.output;
    EXPECT_NE(r.output.find(message), std::string::npos) << args << "\n" << r.output;
  }
  EXPECT_FALSE(fs::exists(sweep_));
  EXPECT_TRUE(fake_.submitted().empty());
}

}  // namespace
}  // namespace rapid
