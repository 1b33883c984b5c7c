// Resuming and partial reruns (docs/design.md §Sweeps): a finished sweep reruns nothing, --only with
// --force reruns exactly the selected jobs, a grid change reruns exactly the jobs it touches,
// and `rapid status` counts what the files say, failed jobs with their errors included.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include "core/dataset_io.hpp"
#include "tests/datasets/dataset_fixtures.hpp"
#include "tests/sweep/sweep_test_util.hpp"

namespace rapid {
namespace {

using namespace sweep_test;
using nlohmann::json;

// A pendulum sweep with a prior algorithm and ddpg over two seeds, its datasets provided.
class SmallSweep : public ::testing::Test {
 protected:
  void SetUp() override {
    grid_ = pendulum_grid("small", {"rapid-rl", "ddpg"}, {0, 1}, 1500);
    write_grid();
    provide_datasets(sweep_, grid_path_);
  }
  void write_grid() { write_json(grid_path_, grid_); }
  Result sweep(const std::string& extra = "") {
    return run_rapid("sweep " + grid_path_.string() + " --jobs 2 --out " + sweep_.string() + " " + extra);
  }
  json status() {
    const Result r = run_rapid("status --json " + sweep_.string());
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return json::parse(r.output);
  }

  testing::ScratchDir dir_;
  fs::path grid_path_ = dir_.path() / "small.json";
  fs::path sweep_ = dir_.path() / "sweep";
  json grid_;
};

TEST_F(SmallSweep, CompletesAndARerunRunsNothing) {
  const Result first = sweep();
  ASSERT_EQ(first.exit_code, 0) << first.output;
  const auto records = comparable_records(sweep_);
  ASSERT_EQ(records.size(), 4u);
  for (const auto& [dir, record] : records) EXPECT_EQ(record["status"], "ok") << dir;
  EXPECT_EQ(records.at("jobs/pendulum/initial/rapid-rl/seed1")["cell"],
            (json{{"scenario", "pendulum"}, {"dataset", "initial"}, {"algo", "rapid-rl"}, {"seed", 1}}));
  EXPECT_EQ(read_json(sweep_ / "grid.json")["reference"]["seed"], 1000);
  const json manifest = read_json(sweep_ / "sweep.json");
  EXPECT_EQ(manifest["status"], "complete");
  EXPECT_EQ(manifest["jobs"]["run"], 4);
  EXPECT_EQ(manifest["jobs"]["skipped_done"], 2);  // the provided reference and dataset jobs
  EXPECT_TRUE(fs::exists(sweep_ / "jobs/pendulum/none/ddpg/seed0/log.txt"));

  const auto before = record_identities(sweep_);
  const Result second = sweep();
  ASSERT_EQ(second.exit_code, 0) << second.output;
  EXPECT_EQ(record_identities(sweep_), before) << "records must be untouched";
  EXPECT_TRUE(jobs_ran(sweep_).empty());
  EXPECT_EQ(read_json(sweep_ / "sweep.json")["jobs"]["skipped_done"], 6);
  EXPECT_EQ(status()["counts"]["ok"], 6);
}

// A record that the reports call corrupt is not done for the runner or `rapid status` either, so
// rerunning the sweep repairs it (one judgement of a record: sweep/cell_record.hpp).
TEST_F(SmallSweep, ACorruptRecordIsNotDoneAndARerunRepairsIt) {
  ASSERT_EQ(sweep().exit_code, 0);
  const fs::path nan_final = sweep_ / "jobs/pendulum/none/ddpg/seed0/record.json";
  const fs::path foreign = sweep_ / "jobs/pendulum/none/ddpg/seed1/record.json";
  const fs::path other_cell = sweep_ / "jobs/pendulum/initial/rapid-rl/seed0/record.json";
  json r = read_json(nan_final);
  r["final"]["return_mean"] = "NaN";
  write_json(nan_final, r);
  r = read_json(foreign);
  r["schema"] = "someone.else/7";
  write_json(foreign, r);
  r = read_json(other_cell);
  r["cell"]["seed"] = 1;  // the hash still matches: only the cell says it is another one
  write_json(other_cell, r);

  const json s = status();
  EXPECT_EQ(s["counts"]["ok"], 3) << s.dump();  // the dataset stage and rapid-rl/seed1
  EXPECT_EQ(s["counts"]["failed"], 3) << s.dump();
  for (const json& job : s["jobs"]) {
    if (job["state"] == "failed") {
      EXPECT_NE(job["detail"].get<std::string>().find("is corrupt"), std::string::npos) << job.dump();
    }
  }

  const Result rerun = sweep();
  ASSERT_EQ(rerun.exit_code, 0) << rerun.output;
  EXPECT_EQ(jobs_ran(sweep_), (std::vector<std::string>{"pendulum/initial/rapid-rl/seed0", "pendulum/none/ddpg/seed0",
                                                       "pendulum/none/ddpg/seed1"}));
  EXPECT_EQ(status()["counts"]["ok"], 6);
  EXPECT_EQ(read_json(nan_final)["final"]["return_mean"].is_number(), true);
}

TEST_F(SmallSweep, OnlyWithForceRerunsExactlyTheSelectedJobs) {
  ASSERT_EQ(sweep().exit_code, 0);
  auto before = record_identities(sweep_);

  // Selected but done: nothing runs without --force.
  ASSERT_EQ(sweep("--only scenario=pendulum,dataset=initial,algo=rapid-rl").exit_code, 0);
  EXPECT_TRUE(jobs_ran(sweep_).empty());

  const Result forced = sweep("--only algo=ddpg,seed=1 --force");
  ASSERT_EQ(forced.exit_code, 0) << forced.output;
  EXPECT_EQ(jobs_ran(sweep_), (std::vector<std::string>{"pendulum/none/ddpg/seed1"}));
  auto after = record_identities(sweep_);
  for (const auto& [dir, identity] : before)
    if (dir == "jobs/pendulum/none/ddpg/seed1") EXPECT_NE(after.at(dir), identity) << dir;
    else EXPECT_EQ(after.at(dir), identity) << dir;

  // A table cell (all its seeds), with its dependencies done and not forced.
  before = after;
  ASSERT_EQ(sweep("--only dataset=initial,algo=rapid-rl --force").exit_code, 0);
  EXPECT_EQ(jobs_ran(sweep_),
            (std::vector<std::string>{"pendulum/initial/rapid-rl/seed0", "pendulum/initial/rapid-rl/seed1"}));
  after = record_identities(sweep_);
  EXPECT_EQ(after.at("jobs/pendulum/none/ddpg/seed0"), before.at("jobs/pendulum/none/ddpg/seed0"));
  EXPECT_NE(after.at("jobs/pendulum/initial/rapid-rl/seed0"), before.at("jobs/pendulum/initial/rapid-rl/seed0"));
}

TEST_F(SmallSweep, AGridChangeRerunsExactlyTheJobsItTouches) {
  // Every sweep's output goes with its failure: this test once failed under load with exit 1 and
  // no word of why.
  const Result initial = sweep();
  ASSERT_EQ(initial.exit_code, 0) << initial.output;
  const auto first = record_identities(sweep_);

  // A new seed: only its cells run.
  grid_["seeds"] = {0, 1, 2};
  write_grid();
  const Result more_seeds = sweep();
  ASSERT_EQ(more_seeds.exit_code, 0) << more_seeds.output;
  EXPECT_EQ(jobs_ran(sweep_), (std::vector<std::string>{"pendulum/initial/rapid-rl/seed2", "pendulum/none/ddpg/seed2"}));
  EXPECT_NE(more_seeds.output.find("seeds: [0,1] → [0,1,2]"), std::string::npos) << more_seeds.output;
  auto now = record_identities(sweep_);
  for (const auto& [dir, identity] : first) EXPECT_EQ(now.at(dir), identity) << dir;

  // Keys that do not enter any job's hash: nothing runs.
  grid_["max_retries"] = 1;
  grid_["description"] = "same jobs";
  write_grid();
  const Result same_jobs = sweep();
  ASSERT_EQ(same_jobs.exit_code, 0) << same_jobs.output;
  EXPECT_TRUE(jobs_ran(sweep_).empty());

  // A config value: every cell of the scenario is stale. Only ddpg is run here (the prior
  // cells would need the dataset stage rebuilt, which needs `rapid dataset build`).
  const auto before_config = record_identities(sweep_);
  grid_["config"]["eval_episodes"] = 3;
  write_grid();
  const Result changed = sweep("--only algo=ddpg");
  ASSERT_EQ(changed.exit_code, 0) << changed.output;
  EXPECT_NE(changed.output.find("config.eval_episodes: 2 → 3"), std::string::npos) << changed.output;
  EXPECT_EQ(jobs_ran(sweep_), (std::vector<std::string>{"pendulum/none/ddpg/seed0", "pendulum/none/ddpg/seed1",
                                                       "pendulum/none/ddpg/seed2"}));
  now = record_identities(sweep_);
  EXPECT_EQ(now.at("jobs/pendulum/initial/rapid-rl/seed0"), before_config.at("jobs/pendulum/initial/rapid-rl/seed0"));
  const json s = status();
  EXPECT_EQ(s["counts"]["ok"], 3);
  EXPECT_EQ(s["counts"]["stale"], 3 + 2);  // the rapid-rl cells and the dataset stage
}

// The same rule for a dataset as for a record: one that does not validate (here cut short) is
// not done, so the dataset job runs again, rebuilds it, and its cells rerun on the new file.
TEST_F(SmallSweep, ATruncatedDatasetIsNotDoneAndARerunRebuildsIt) {
  fs::remove_all(sweep_);  // the sweep builds its reference and datasets itself
  ASSERT_EQ(sweep().exit_code, 0);
  const fs::path dataset = sweep_ / "datasets/pendulum/initial.h5";
  fs::resize_file(dataset, fs::file_size(dataset) / 2);
  const json before = status();
  EXPECT_EQ(before["counts"]["ok"], 6 - 1 - 2) << "the dataset job and its two cells are not done";
  for (const json& job : before["jobs"])
    if (job["job"] == "pendulum/datasets") {
      EXPECT_EQ(job["state"], "stale");
      EXPECT_NE(job["detail"].get<std::string>().find("initial.h5: unreadable HDF5 file (truncated file"),
                std::string::npos) << job["detail"];
    }

  const Result rerun = sweep();
  ASSERT_EQ(rerun.exit_code, 0) << rerun.output;
  const auto ran = jobs_ran(sweep_);
  EXPECT_NE(std::find(ran.begin(), ran.end(), "pendulum/datasets"), ran.end()) << rerun.output;
  EXPECT_GT(read_dataset(dataset.string()).size(), 0u);
  const auto records = comparable_records(sweep_);
  for (const char* cell : {"jobs/pendulum/initial/rapid-rl/seed0", "jobs/pendulum/initial/rapid-rl/seed1"})
    EXPECT_EQ(records.at(cell)["status"], "ok") << cell;
  const json st = status();
  EXPECT_EQ(st["counts"]["ok"], 6) << st.dump(1);
}

TEST_F(SmallSweep, StatusCountsStatesAndShowsTheFailedJobsError) {
  // A dataset `rapid run` refuses makes its cells fail (exit 2, nothing written), so the sweep
  // does not retry it. (Its actions lie outside [-1, 1]: a file that does not open would not do,
  // since the dataset job is not done with it and builds it again.)
  grid_["datasets"] = {"initial", "medium"};
  grid_["seeds"] = {0};
  grid_["max_retries"] = 1;
  write_grid();
  provide_datasets(sweep_, grid_path_);
  write_dataset((sweep_ / "datasets/pendulum/medium.h5").string(), testing::make_dataset(3, 1, {50}));

  const Result r = sweep();
  EXPECT_EQ(r.exit_code, 1) << r.output;
  const json manifest = read_json(sweep_ / "sweep.json");
  EXPECT_EQ(manifest["status"], "failed");
  EXPECT_EQ(manifest["retries"], 0) << "bad input is not retried";
  ASSERT_EQ(manifest["failures"].size(), 1u);
  EXPECT_EQ(manifest["failures"][0]["job"], "pendulum/medium/rapid-rl/seed0");
  EXPECT_EQ(read_json(sweep_ / "jobs/pendulum/medium/rapid-rl/seed0/outcome.json")["attempts"], 1);
  EXPECT_FALSE(fs::exists(sweep_ / "jobs/pendulum/medium/rapid-rl/seed0/record.json"));

  // One more seed in the folder's grid: its cells are pending.
  json folder_grid = read_json(sweep_ / "grid.json");
  folder_grid["seeds"] = {0, 1};
  write_json(sweep_ / "grid.json", folder_grid);
  const json s = status();
  EXPECT_EQ(s["counts"]["ok"], 2 + 2);  // the dataset stage, rapid-rl/initial and ddpg of seed 0
  EXPECT_EQ(s["counts"]["failed"], 1);
  EXPECT_EQ(s["counts"]["pending"], 3);
  EXPECT_EQ(s["counts"]["running"], 0);
  for (const json& job : s["jobs"])
    if (job["state"] == "failed") {
      EXPECT_EQ(job["job"], "pendulum/medium/rapid-rl/seed0");
      EXPECT_NE(job["detail"].get<std::string>().find("medium.h5"), std::string::npos) << job["detail"];
    }

  const Result text = run_rapid("status " + sweep_.string());
  EXPECT_EQ(text.exit_code, 0);
  EXPECT_NE(text.output.find("  failed    1\n"), std::string::npos) << text.output;
  EXPECT_NE(text.output.find("failed jobs:\n  pendulum/medium/rapid-rl/seed0: failed: "), std::string::npos) << text.output;
}

}  // namespace
}  // namespace rapid

namespace rapid {
namespace {

using namespace sweep_test;
using nlohmann::json;

// The whole graph with `rapid dataset build`: reference agent → datasets → cells, then a change
// of the reference settings reruns the dataset stage and the prior cells but not ddpg.
TEST(SweepGraph, BuildsTheDatasetStageThenTheCellsAndRebuildsOnlyWhatAReferenceChangeTouches) {
  testing::ScratchDir dir;
  const fs::path grid_path = dir.path() / "chain.json", sweep = dir.path() / "sweep";
  json grid = pendulum_grid("chain", {"rapid-rl", "ddpg"}, {0}, 1500);
  write_json(grid_path, grid);
  const std::string args = "sweep " + grid_path.string() + " --jobs 2 --out " + sweep.string();

  const Result first = run_rapid(args);
  ASSERT_EQ(first.exit_code, 0) << first.output;
  EXPECT_EQ(jobs_ran(sweep), (std::vector<std::string>{"pendulum/reference", "pendulum/datasets",
                                                      "pendulum/initial/rapid-rl/seed0", "pendulum/none/ddpg/seed0"}));
  EXPECT_TRUE(fs::exists(sweep / "datasets/pendulum/initial.h5"));
  ASSERT_EQ(run_rapid(args).exit_code, 0);
  EXPECT_TRUE(jobs_ran(sweep).empty());

  const auto before = record_identities(sweep);
  grid["reference"]["transitions"] = 1200;
  write_json(grid_path, grid);
  const Result changed = run_rapid(args);
  ASSERT_EQ(changed.exit_code, 0) << changed.output;
  EXPECT_EQ(jobs_ran(sweep), (std::vector<std::string>{"pendulum/reference", "pendulum/datasets",
                                                      "pendulum/initial/rapid-rl/seed0"}));
  EXPECT_EQ(record_identities(sweep).at("jobs/pendulum/none/ddpg/seed0"), before.at("jobs/pendulum/none/ddpg/seed0"));
}

}  // namespace
}  // namespace rapid
