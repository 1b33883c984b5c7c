// Whole sweeps through a real Slurm (docs/cluster.md). Skipped unless RAPID_SLURM_TESTS=1 and `sinfo`
// answers: scripts/test-slurm starts a throwaway single-node Slurm (scripts/slurm-local), runs
// these and stops it.
//  - The smoke grid (or $RAPID_SLURM_TEST_GRID) gives the same records and datasets through
//    Slurm as through the local backend, and `rapid status` sees every job ok from the files.
//  - A task that fails shows in `rapid status` (with its retries) and runs again, alone, on the
//    next submission.
//  - A failed reference agent stops its scenario's later arrays (afterok) and nothing else: the
//    other scenario and the cells that need no dataset run; status shows the failure and the
//    blocked jobs, and the next submission runs everything that is left.
//  - --decide runs its looks as follow-up jobs, to the same looks, records and decisions as the
//    local backend's --decide, and refreshes the reports when the looks stop.
//  - `rapid tune --backend slurm` submits a rung an invocation and, run again until every search
//    has its winner, writes the tuned.json and trial records the local backend's tune does.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <fstream>

#include "core/dataset_io.hpp"
#include "tests/datasets/dataset_fixtures.hpp"
#include "tests/slurm/slurm_test_util.hpp"
#include "tests/sweep/sweep_test_util.hpp"

namespace rapid {
namespace {

using namespace sweep_test;
using namespace slurm_test;
using nlohmann::json;

constexpr double kTimeoutS = 900;

class SlurmCluster : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string why;
    if (!slurm_available(why)) GTEST_SKIP() << why;
  }
  // Submits and waits for the arrays to leave the queue; returns the output of the submission.
  Result submit_and_wait(const fs::path& grid, const fs::path& out, const std::string& extra = "") {
    const Result r = run_rapid("sweep " + grid.string() + " --backend slurm --array-parallelism 2 --out " + out.string() +
                               " " + extra);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_TRUE(wait_for_jobs(submitted_ids(r.output), kTimeoutS)) << "the arrays did not finish in time\n" << r.output;
    return r;
  }
  json status(const fs::path& sweep) {
    const Result r = run_rapid("status --json " + sweep.string());
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return json::parse(r.output);
  }
  static std::string slurp(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }
  // The task output of the first task of the array `name` (e.g. cells-merge) a submission printed.
  static std::string task_output(const fs::path& sweep, const std::string& name, const Result& submission) {
    const auto at = submission.output.find("  " + name + ": job ");
    if (at == std::string::npos) return "";
    const std::string id = submission.output.substr(at + name.size() + 8, submission.output.find(',', at) - at - name.size() - 8);
    return slurp(sweep / "slurm" / (name + "_" + id + "_0.out"));
  }

  // Every job a submission to `sweep` recorded, follow-ups included, until none is queued and
  // decide.json says the looks stopped; false on timeout.
  static bool wait_for_decide(const fs::path& sweep, double timeout_s) {
    const auto start = std::chrono::steady_clock::now();
    const auto submitted = [&] {
      std::vector<std::string> ids;
      const json submissions = read_json(sweep / "slurm/submissions.json");
      for (const json& submission : submissions["submissions"])
        for (const json& a : submission["arrays"]) ids.push_back(a["job_id"].get<std::string>());
      return ids;
    };
    for (;;) {
      const std::vector<std::string> ids = submitted();
      const double left = timeout_s - std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      if (left <= 0 || !wait_for_jobs(ids, left)) return false;
      if (submitted() == ids && read_json(sweep / "decide.json").contains("stopped")) return true;
    }
  }

  testing::ScratchDir dir_;
};

TEST_F(SlurmCluster, GridRecordsEqualTheLocalBackends) {
  const char* env = std::getenv("RAPID_SLURM_TEST_GRID");
  const fs::path grid = env && *env ? fs::path(env) : fs::path(RAPID_SOURCE_DIR) / "experiments/grids/smoke.json";
  const fs::path local = dir_.path() / "local", slurm = dir_.path() / "slurm";

  const Result l = run_rapid("sweep " + grid.string() + " --jobs 2 --out " + local.string());
  ASSERT_EQ(l.exit_code, 0) << l.output;
  const Result s = submit_and_wait(grid, slurm);

  const json st = status(slurm);
  EXPECT_EQ(st["counts"]["ok"], st["jobs"].size()) << st.dump(1);
  const auto local_records = comparable_run_records(local, slurm);
  const auto slurm_records = comparable_run_records(slurm, local);
  ASSERT_FALSE(local_records.empty());
  EXPECT_EQ(slurm_records.size(), local_records.size());
  for (const auto& [path, record] : local_records) {
    ASSERT_TRUE(slurm_records.count(path)) << path;
    EXPECT_EQ(slurm_records.at(path), record) << path;
  }
  const auto datasets = dataset_files(local);
  EXPECT_EQ(dataset_files(slurm), datasets);
  for (const auto& file : datasets)
    EXPECT_TRUE(testing::bit_identical(read_dataset((local / file).string()), read_dataset((slurm / file).string())))
        << file;
  for (const json& job : st["jobs"]) {
    const json outcome = read_json(slurm / job["dir"].get<std::string>() / "outcome.json");
    EXPECT_EQ(outcome["state"], "ok") << job["job"];
    EXPECT_EQ(outcome["attempts"], 1) << job["job"];
  }
  EXPECT_NE(task_output(slurm, "cells-lane-drop", s).find("rapid sweep task: ok "), std::string::npos) << s.output;

  const Result again = run_rapid("sweep " + grid.string() + " --backend slurm --out " + slurm.string());
  EXPECT_EQ(again.exit_code, 0) << again.output;
  EXPECT_NE(again.output.find("nothing to submit"), std::string::npos) << again.output;
}

TEST_F(SlurmCluster, AFailedTaskShowsInStatusAndRunsAgainOnTheNextSubmission) {
  json g = pendulum_grid("fails", {"rapid-rl", "ddpg"}, {0, 1}, 400);
  g["max_retries"] = 1;
  const fs::path grid = dir_.path() / "fails.json", sweep = dir_.path() / "sweep";
  write_json(grid, g);
  submit_and_wait(grid, sweep);
  ASSERT_EQ(status(sweep)["counts"]["ok"], 6);

  // A dataset `rapid run` refuses as bad input (exit 2, nothing written), so the selected cell
  // fails at once, without a retry. (Forced: its ok record is otherwise done. Its actions lie
  // outside [-1, 1]: a file that does not open would make the dataset job build it again.)
  const fs::path dataset = sweep / "datasets/pendulum/initial.h5";
  const std::string good = slurp(dataset);
  write_dataset(dataset.string(), testing::make_dataset(3, 1, {50}));
  const Result failing = submit_and_wait(grid, sweep, "--only algo=rapid-rl,seed=0 --force");
  EXPECT_NE(task_output(sweep, "cells-pendulum", failing).find("failed pendulum/initial/rapid-rl/seed0 after 1 attempt"),
            std::string::npos)
      << failing.output;

  json st = status(sweep);
  EXPECT_EQ(st["counts"]["failed"], 1) << st.dump(1);
  EXPECT_EQ(read_json(sweep / "jobs/pendulum/initial/rapid-rl/seed0/outcome.json")["attempts"], 1);
  const Result text = run_rapid("status " + sweep.string());
  EXPECT_NE(text.output.find("failed jobs:\n  pendulum/initial/rapid-rl/seed0: failed: "), std::string::npos) << text.output;
  std::ofstream(dataset, std::ios::trunc | std::ios::binary) << good;
  // Its old record fits the restored dataset again; forcing the rerun gives a new one.
  st = status(sweep);
  EXPECT_EQ(st["counts"]["ok"], 6) << st.dump(1);

  const auto before = record_identities(sweep);
  const Result rerun = submit_and_wait(grid, sweep, "--only algo=rapid-rl,seed=0 --force");
  EXPECT_NE(rerun.output.find("submitted 1 job to Slurm"), std::string::npos) << rerun.output;
  EXPECT_EQ(status(sweep)["counts"]["ok"], 6);
  const auto after = record_identities(sweep);
  for (const auto& [path, identity] : before) {
    if (path == "jobs/pendulum/initial/rapid-rl/seed0") continue;
    EXPECT_EQ(after.at(path), identity) << path;
  }
  EXPECT_NE(after.at("jobs/pendulum/initial/rapid-rl/seed0"), before.at("jobs/pendulum/initial/rapid-rl/seed0"));
}

TEST_F(SlurmCluster, AFailedReferenceStopsOnlyItsScenarioUntilTheNextSubmission) {
  json g = pendulum_grid("blocked", {"rapid-rl", "ddpg"}, {0}, 400);
  g["scenarios"] = {"pendulum", "merge"};
  g["max_retries"] = 0;
  const fs::path grid = dir_.path() / "blocked.json", sweep = dir_.path() / "sweep";
  write_json(grid, g);
  // A file where the pendulum's dataset folder belongs: its reference agent cannot be saved.
  fs::create_directories(sweep / "datasets");
  std::ofstream(sweep / "datasets/pendulum") << "in the way";
  // The folder now holds a file but no grid.json: --force lets the sweep write into it.
  const Result first = submit_and_wait(grid, sweep, "--force");
  // Per scenario: references, datasets, the rapid-rl cell after them, the ddpg cell on its own.
  ASSERT_EQ(submitted_ids(first.output).size(), 8u) << first.output;

  const json st = status(sweep);
  EXPECT_EQ(st["counts"]["failed"], 1) << st.dump(1);   // the pendulum reference
  EXPECT_EQ(st["counts"]["blocked"], 2) << st.dump(1);  // its dataset job and its rapid-rl cell
  EXPECT_EQ(st["counts"]["ok"], 5) << st.dump(1);       // the pendulum ddpg cell and all of merge
  EXPECT_TRUE(fs::exists(sweep / "jobs/pendulum/none/ddpg/seed0/record.json"));
  EXPECT_TRUE(fs::exists(sweep / "jobs/merge/initial/rapid-rl/seed0/record.json"));

  fs::remove(sweep / "datasets/pendulum");
  const Result second = submit_and_wait(grid, sweep);
  EXPECT_NE(second.output.find("submitted 3 jobs to Slurm (5 already done)"), std::string::npos) << second.output;
  EXPECT_EQ(status(sweep)["counts"]["ok"], 8) << status(sweep).dump(1);
}

TEST_F(SlurmCluster, DecideRunsItsLooksAsFollowUpJobsAsTheLocalBackendDoes) {
  json g = pendulum_grid("decide", {"rapid-rl", "ddpg"}, {0, 1}, 400);
  g["profile"] = "short";
  const fs::path grid = dir_.path() / "decide.json", local = dir_.path() / "local", slurm = dir_.path() / "slurm";
  write_json(grid, g);
  const std::string decide = " --no-animations --decide --max-seeds 4 --block 1 --out ";
  const Result l = run_rapid("sweep " + grid.string() + " --jobs 2" + decide + local.string());
  ASSERT_EQ(l.exit_code, 0) << l.output;

  const Result s = run_rapid("sweep " + grid.string() + " --backend slurm --array-parallelism 2" + decide + slurm.string());
  ASSERT_EQ(s.exit_code, 0) << s.output;
  EXPECT_NE(s.output.find("the looks of --decide follow in job "), std::string::npos) << s.output;
  ASSERT_TRUE(wait_for_decide(slurm, kTimeoutS)) << "the looks did not finish in time";

  const json local_plan = read_json(local / "decide.json"), slurm_plan = read_json(slurm / "decide.json");
  EXPECT_EQ(slurm_plan["looks"], local_plan["looks"]);
  EXPECT_EQ(slurm_plan["stopped"], local_plan["stopped"]);
  EXPECT_EQ(read_json(slurm / "grid.json")["seeds"], read_json(local / "grid.json")["seeds"]);
  const auto local_records = comparable_run_records(local, slurm);
  const auto slurm_records = comparable_run_records(slurm, local);
  EXPECT_EQ(slurm_records.size(), local_records.size());
  for (const auto& [path, record] : local_records) {
    ASSERT_TRUE(slurm_records.count(path)) << path;
    EXPECT_EQ(slurm_records.at(path), record) << path;
  }
  // The last follow-up refreshed the reports: the same decisions, at alpha over the same looks.
  int code = 0;
  ASSERT_TRUE(fs::exists(slurm / "summary.json")) << capture("squeue -a -l 2>&1", code) << slurm_plan.dump(1)
                                                  << read_json(slurm / "slurm/submissions.json").dump(1);
  EXPECT_EQ(read_json(slurm / "summary.json")["decisions"], read_json(local / "summary.json")["decisions"]);

  // Again: the looks replay from the records and nothing is submitted.
  const std::size_t submissions = read_json(slurm / "slurm/submissions.json")["submissions"].size();
  const Result again = run_rapid("sweep " + grid.string() + " --backend slurm" + decide + slurm.string());
  EXPECT_EQ(again.exit_code, 0) << again.output;
  EXPECT_NE(again.output.find("nothing to submit"), std::string::npos) << again.output;
  EXPECT_EQ(read_json(slurm / "slurm/submissions.json")["submissions"].size(), submissions);
  EXPECT_EQ(read_json(slurm / "decide.json")["looks"], local_plan["looks"]);
}

TEST_F(SlurmCluster, TuneSubmitsARungAnInvocationToTheLocalBackendsWinner) {
  const TuneFiles in = write_tiny_tune(dir_.path());
  const fs::path local = dir_.path() / "local", slurm = dir_.path() / "slurm";
  const std::string tune = "tune " + in.grid.string() + " --space " + in.space.string();
  const Result l = run_rapid(tune + " --jobs 2 --out " + local.string());
  ASSERT_EQ(l.exit_code, 0) << l.output;

  // Rung 1 (4 candidates), rung 2 (the better 2), the confirmation of the winner (not the
  // defaults), then the results: four invocations.
  int invocations = 0;
  for (; invocations < 6 && !fs::exists(slurm / "tuned.json"); ++invocations) {
    const Result s = run_rapid(tune + " --backend slurm --out " + slurm.string());
    ASSERT_EQ(s.exit_code, 0) << s.output;
    if (fs::exists(slurm / "tuned.json")) {
      EXPECT_NE(s.output.find("every search has its winner"), std::string::npos) << s.output;
      break;
    }
    EXPECT_NE(s.output.find("this rung's trials are submitted"), std::string::npos) << s.output;
    ASSERT_FALSE(submitted_ids(s.output).empty()) << s.output;
    ASSERT_TRUE(wait_for_jobs(submitted_ids(s.output), kTimeoutS)) << "the rung did not finish in time\n" << s.output;
  }
  EXPECT_EQ(invocations, 3);  // two rungs and the confirmation submitted; the fourth invocation wrote the results
  nlohmann::json a = read_json(slurm / "tuned.json"), b = read_json(local / "tuned.json");
  for (nlohmann::json* t : {&a, &b}) {
    t->erase("wall_s");
    (*t)["results"]["pendulum"]["ddpg"].erase("wall_s");
  }
  EXPECT_EQ(a, b);
  EXPECT_EQ(read_json(slurm / "tuned-grid.json"), read_json(local / "tuned-grid.json"));
  for (const std::string folder : {"c0", "c1", "c2", "c3", "confirm/c0"}) {
    const fs::path c = folder;
    const auto local_records = comparable_run_records(local / c, slurm / c);
    const auto slurm_records = comparable_run_records(slurm / c, local / c);
    EXPECT_EQ(slurm_records.size(), local_records.size()) << c;
    for (const auto& [path, record] : local_records) {
      ASSERT_TRUE(slurm_records.count(path)) << c / path;
      EXPECT_EQ(slurm_records.at(path), record) << c / path;
    }
  }
}

}  // namespace
}  // namespace rapid
