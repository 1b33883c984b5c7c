// scripts/campaign-records (docs/sweeps.md, "A campaign that outlives its machine"): the records a
// finished part of a sweep left, saved into an archive and restored into a fresh folder on another
// machine, make the same sweep command run nothing it already ran; records of another code
// revision, or a restore over files that differ, are refused with exit 2 and nothing written; the
// script writes only where it is told, through no name another user could plant a link at.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <string>

#include "core/atomic_file.hpp"
#include "tests/sweep/sweep_test_util.hpp"
#include "tests/cli_runner.hpp"
#include "tests/datasets/dataset_fixtures.hpp"

namespace rapid {
namespace {

using namespace sweep_test;
using nlohmann::json;

Result run_script(const std::string& args) {
  const test::CliOutput out =
      test::shell_output(std::string(RAPID_SOURCE_DIR) + "/scripts/campaign-records " + args + " 2>&1");
  return Result{out.exit_code, out.text};
}

class CampaignRecords : public ::testing::Test {
 protected:
  void SetUp() override {
    write_json(grid_path_, pendulum_grid("campaign", {"rapid-rl", "ddpg"}, {0, 1}, 1500));
    provide_datasets(first_, grid_path_);
    const Result r = sweep(first_);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    revision_ = read_json(first_ / "jobs/pendulum/none/ddpg/seed0/record.json")["provenance"]["code_revision"];
  }
  Result sweep(const fs::path& folder) {
    return run_rapid("sweep " + grid_path_.string() + " --jobs 2 --out " + folder.string());
  }

  testing::ScratchDir dir_;
  fs::path grid_path_ = dir_.path() / "campaign.json";
  fs::path first_ = dir_.path() / "first";    // the machine that was replaced
  fs::path second_ = dir_.path() / "second";  // the next one
  fs::path archive_ = dir_.path() / "saved/campaign.tar.xz";
  std::string revision_;
};

TEST_F(CampaignRecords, RestoredRecordsAreNotRunAgain) {
  // One run's record is lost before the save (it was still running): it must run again.
  fs::remove(first_ / "jobs/pendulum/initial/rapid-rl/seed1/record.json");
  const Result saved = run_script("save " + first_.string() + " " + archive_.string() + " --revision " + revision_);
  ASSERT_EQ(saved.exit_code, 0) << saved.output;
  EXPECT_NE(saved.output.find("saved 3 records"), std::string::npos) << saved.output;

  // Restored into a fresh folder, as on a new machine: the sweep folder it makes is one that
  // `rapid sweep --out` and `rapid status` accept as it is (no --force).
  const Result restored = run_script("restore " + archive_.string() + " " + second_.string());
  ASSERT_EQ(restored.exit_code, 0) << restored.output;
  const Result restored_status = run_rapid("status " + second_.string());
  ASSERT_EQ(restored_status.exit_code, 0) << restored_status.output;
  provide_datasets(second_, grid_path_);  // what --reuse-datasets rebuilds on the new machine
  const Result status = run_rapid("status --json " + second_.string());
  ASSERT_EQ(status.exit_code, 0) << status.output;
  std::map<std::string, std::string> run_states;  // the runs' states, the dataset jobs left out
  const json listed = json::parse(status.output);
  for (const auto& job : listed["jobs"])
    if (job["job"].get<std::string>().find("/seed") != std::string::npos) run_states[job["job"]] = job["state"];
  const std::map<std::string, std::string> expected = {{"pendulum/initial/rapid-rl/seed0", "ok"},
                                                       {"pendulum/initial/rapid-rl/seed1", "pending"},
                                                       {"pendulum/none/ddpg/seed0", "ok"},
                                                       {"pendulum/none/ddpg/seed1", "ok"}};
  EXPECT_EQ(run_states, expected) << status.output;
  const Result resumed = sweep(second_);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_EQ(jobs_ran(second_), std::vector<std::string>{"pendulum/initial/rapid-rl/seed1"});

  // The sweep finished on the new machine holds what it would have held on the old one.
  ASSERT_EQ(sweep(first_).exit_code, 0);
  EXPECT_EQ(comparable_records(second_), comparable_records(first_));
}

TEST_F(CampaignRecords, AFailedRunIsNotSaved) {
  const fs::path failed = first_ / "jobs/pendulum/none/ddpg/seed1/record.json";
  json r = read_json(failed);
  r["status"] = "diverged";
  write_json(failed, r);
  const Result saved = run_script("save " + first_.string() + " " + archive_.string());
  ASSERT_EQ(saved.exit_code, 0) << saved.output;
  EXPECT_NE(saved.output.find("saved 3 records"), std::string::npos) << saved.output;
}

TEST_F(CampaignRecords, RecordsOfAnotherRevisionAreRefused) {
  const fs::path other = first_ / "jobs/pendulum/none/ddpg/seed1/record.json";
  json r = read_json(other);
  r["provenance"]["code_revision"] = "0000000";
  write_json(other, r);

  Result saved = run_script("save " + first_.string() + " " + archive_.string());
  EXPECT_EQ(saved.exit_code, 2);
  EXPECT_NE(saved.output.find("records of 2 revisions"), std::string::npos) << saved.output;
  EXPECT_FALSE(fs::exists(archive_));

  saved = run_script("save " + first_.string() + " " + archive_.string() + " --revision " + revision_);
  EXPECT_EQ(saved.exit_code, 2);
  EXPECT_NE(saved.output.find("revision 0000000 are not of --revision " + revision_), std::string::npos) << saved.output;
  EXPECT_FALSE(fs::exists(archive_));
}

TEST_F(CampaignRecords, RestoreNeverOverwritesAFileThatDiffers) {
  ASSERT_EQ(run_script("save " + first_.string() + " " + archive_.string()).exit_code, 0);
  const Result wrong = run_script("restore " + archive_.string() + " " + second_.string() + " --revision 0000000");
  EXPECT_EQ(wrong.exit_code, 2) << wrong.output;
  EXPECT_FALSE(fs::exists(second_));

  provide_datasets(second_, grid_path_);
  ASSERT_EQ(sweep(second_).exit_code, 0);
  const fs::path changed = second_ / "jobs/pendulum/none/ddpg/seed0/record.json";
  json r = read_json(changed);
  r["final"]["return_mean"] = 1.0;
  write_json(changed, r);
  const auto before = record_identities(second_);
  const Result refused = run_script("restore " + archive_.string() + " " + second_.string());
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_NE(refused.output.find("exists and differs"), std::string::npos) << refused.output;
  EXPECT_EQ(std::count(refused.output.begin(), refused.output.end(), '\n'), 1) << refused.output;
  EXPECT_EQ(record_identities(second_), before);
}

// Issue #67: a restore writes nothing outside its folder, even where a folder inside it is a
// symbolic link to elsewhere; and a folder that is a file is one line, not a traceback.
TEST_F(CampaignRecords, RestoreWritesOnlyInsideItsFolder) {
  ASSERT_EQ(run_script("save " + first_.string() + " " + archive_.string()).exit_code, 0);
  const fs::path elsewhere = dir_.path() / "elsewhere";
  fs::create_directories(elsewhere);
  fs::create_directories(second_);
  fs::create_directory_symlink(elsewhere, second_ / "jobs");
  const Result refused = run_script("restore " + archive_.string() + " " + second_.string());
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find("is a symbolic link; restore writes only inside"), std::string::npos) << refused.output;
  EXPECT_TRUE(fs::is_empty(elsewhere));
  EXPECT_FALSE(fs::exists(second_ / "grid.json"));

  const fs::path a_file = dir_.path() / "a-file";
  write_file_atomic(a_file.string(), "kept\n");
  const Result onto_file = run_script("restore " + archive_.string() + " " + a_file.string());
  EXPECT_EQ(onto_file.exit_code, 2) << onto_file.output;
  EXPECT_EQ(onto_file.output, "campaign-records: '" + a_file.string() + "' exists and is not a folder; restore into a fresh folder\n");
  EXPECT_EQ(read_file(a_file.string()), "kept\n");
}

// Issue #67: the temporary files of save and restore have names nobody can guess, so a symbolic
// link planted at the old names (ARCHIVE.tmp, TARGET.tmp) is never written through.
TEST_F(CampaignRecords, APlantedLinkAtATemporaryNameIsNotFollowed) {
  const fs::path victim = dir_.path() / "victim";
  write_file_atomic(victim.string(), "untouched\n");
  fs::create_directories(archive_.parent_path());
  fs::create_symlink(victim, archive_.string() + ".tmp");
  ASSERT_EQ(run_script("save " + first_.string() + " " + archive_.string()).exit_code, 0);
  fs::create_directories(second_);
  fs::create_symlink(victim, (second_ / "grid.json").string() + ".tmp");
  const Result restored = run_script("restore " + archive_.string() + " " + second_.string());
  ASSERT_EQ(restored.exit_code, 0) << restored.output;
  EXPECT_EQ(read_file(victim.string()), "untouched\n");
  EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(second_ / "grid.json")));
  for (const auto& entry : fs::recursive_directory_iterator(archive_.parent_path()))
    EXPECT_TRUE(entry.path() == archive_ || entry.path().string() == archive_.string() + ".tmp") << entry.path();
}

// Issue #67: an archive member far larger than any campaign file is refused before it is read
// (a 5 GB member of zeros ended in MemoryError and a traceback), and a full standard output is
// one line and exit 1, not the interpreter's complaint.
TEST_F(CampaignRecords, OversizedMembersAndAFullOutputAreOneLine) {
  const fs::path big = dir_.path() / "big";
  fs::create_directories(big / "jobs/a");
  const test::CliOutput made = test::shell_output("cd " + big.string() +
      " && head -c 70000000 /dev/zero > jobs/a/record.json && tar -cJf ../big.tar.xz jobs/a/record.json 2>&1");
  ASSERT_EQ(made.exit_code, 0) << made.text;
  const Result listed = run_script("list " + (dir_.path() / "big.tar.xz").string());
  EXPECT_EQ(listed.exit_code, 2) << listed.output;
  EXPECT_NE(listed.output.find("'jobs/a/record.json' holds 70000000 bytes, more than a campaign's file"), std::string::npos)
      << listed.output;
  EXPECT_EQ(std::count(listed.output.begin(), listed.output.end(), '\n'), 1) << listed.output;

  ASSERT_EQ(run_script("save " + first_.string() + " " + archive_.string()).exit_code, 0);
  const test::CliOutput full = test::shell_output(std::string(RAPID_SOURCE_DIR) + "/scripts/campaign-records list " +
                                                  archive_.string() + " 2>&1 >/dev/full");
  EXPECT_EQ(full.exit_code, 1) << full.text;
  EXPECT_EQ(full.text, "campaign-records: cannot write to standard output: No space left on device\n");
}

}  // namespace
}  // namespace rapid
