// `rapid dataset build` on the pendulum (seconds): the reference agent's checkpoints, the four
// datasets with their metadata, and reuse of up-to-date stages.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "core/atomic_file.hpp"
#include "core/dataset_io.hpp"
#include "core/dataset_mix.hpp"
#include "core/dataset_stats.hpp"
#include "core/mlp.hpp"
#include "tests/cli_runner.hpp"
#include "tests/datasets/dataset_fixtures.hpp"

using namespace rapid;
using test::rapid_cli;
namespace fs = std::filesystem;

namespace {

// A pendulum grid with a small budget; the reference agent trains 2,000 steps and each dataset
// holds 1,000 transitions (5 episodes).
void write_grid(const std::string& path, long transitions) {
  const nlohmann::json grid = {
      {"name", "tiny"},
      {"scenarios", {"pendulum"}},
      {"datasets", {"initial", "final+medium"}},
      {"algos", {"rapid-rl"}},
      {"seeds", {0}},
      {"config", {{"steps", 2000}, {"warmup_steps", 200}, {"eval_every", 1000}, {"eval_episodes", 2}}},
      {"reference", {{"seed", 1000}, {"transitions", transitions}, {"noise_std", 0.1}}}};
  write_file_atomic(path, grid.dump());
}

fs::file_time_type mtime(const std::string& p) { return fs::last_write_time(p); }

}  // namespace

TEST(DatasetBuild, WritesCheckpointsDatasetsAndReusesThem) {
  rapid::testing::ScratchDir dir;
  write_grid(dir.file("grid.json"), 1000);
  const std::string cmd = "dataset build --scenario pendulum --grid " + dir.file("grid.json") + " --dir " + dir.file("data");
  const auto first = rapid_cli(cmd, /*with_stderr=*/true);
  ASSERT_EQ(first.exit_code, 0) << first.text;
  const std::string out = dir.file("data/pendulum");
  for (const char* f : {"reference/record.json", "reference/actor_200.ckpt", "reference/actor_1000.ckpt",
                        "reference/actor.ckpt", "initial.h5", "medium.h5", "final.h5", "final+medium.h5", "build.json"})
    EXPECT_TRUE(fs::exists(out + "/" + f)) << f;
  EXPECT_EQ(nlohmann::json::parse(read_file(out + "/reference/record.json"))["cell"]["seed"], 1000);
  // The collection reported how far it got (three sources of 1,000 transitions), for `rapid status`.
  const auto progress = nlohmann::json::parse(read_file(out + "/progress.json"));
  EXPECT_EQ(progress["step"], 3000);
  EXPECT_EQ(progress["steps"], 3000);

  const Dataset initial = read_dataset(out + "/initial.h5", {3, 1, "pendulum"});
  const Dataset final_data = read_dataset(out + "/final.h5", {3, 1, "pendulum"});
  const Dataset mixed = read_dataset(out + "/final+medium.h5", {3, 1, "pendulum"});
  EXPECT_EQ(initial.size(), 1000u);
  EXPECT_EQ(initial.metadata.at("scenario"), "pendulum");
  EXPECT_EQ(initial.metadata.at("seed"), "1000");
  EXPECT_NE(initial.metadata.at("source_checkpoint").find("actor_200"), std::string::npos);
  // Read back what the source actors had learned: `initial` at decision 200 is the first decision
  // after the warm-up (200), so one update; `medium` at 1,000 has 801; the metadata says the same.
  std::int64_t updates = -1;
  Mlp::load(out + "/reference/actor_200.ckpt", &updates);
  EXPECT_EQ(updates, 1);
  Mlp::load(out + "/reference/actor_1000.ckpt", &updates);
  EXPECT_EQ(updates, 801);
  Mlp::load(out + "/reference/actor.ckpt", &updates);
  EXPECT_EQ(updates, 1801);
  EXPECT_EQ(initial.metadata.at("source_updates"), "1");
  EXPECT_EQ(mixed.metadata.at("source_updates"), "final 1801, medium 801");
  EXPECT_FALSE(initial.metadata.at("code_revision").empty());
  // Half of each source in whole episodes: up to the first episode end at or past N/2.
  const Dataset medium = read_dataset(out + "/medium.h5");
  EXPECT_EQ(mixed.size(), half_by_episodes_size(final_data) + half_by_episodes_size(medium));
  EXPECT_EQ(half_by_episodes_size(final_data), 600u);  // 200-step episodes: 3 of 5
  // The first half of final+medium is final's first episodes, bit for bit.
  EXPECT_EQ(mixed.observations.leftCols(200), final_data.observations.leftCols(200));
  EXPECT_LE(initial.actions.cwiseAbs().maxCoeff(), 1.0f);

  // Rerunning reuses both stages: nothing is rewritten.
  const auto ref_time = mtime(out + "/reference/record.json"), data_time = mtime(out + "/initial.h5");
  ASSERT_EQ(rapid_cli(cmd).exit_code, 0);
  EXPECT_EQ(mtime(out + "/reference/record.json"), ref_time);
  EXPECT_EQ(mtime(out + "/initial.h5"), data_time);

  // A changed collection setting redoes the datasets but keeps the reference agent; the
  // temporaries a killed earlier build left beside the datasets go.
  write_grid(dir.file("grid.json"), 600);
  write_file_atomic(out + "/initial.h5.tmp.4242.0", "half a dataset");
  write_file_atomic(out + "/build.json.tmp.4242", "half a manifest");
  ASSERT_EQ(rapid_cli(cmd).exit_code, 0);
  EXPECT_FALSE(fs::exists(out + "/initial.h5.tmp.4242.0"));
  EXPECT_FALSE(fs::exists(out + "/build.json.tmp.4242"));
  EXPECT_EQ(mtime(out + "/reference/record.json"), ref_time);
  EXPECT_EQ(read_dataset(out + "/initial.h5").size(), 600u);
}

// The flow profile's budget rule: the reference trains L = reference.steps, `initial` and `medium`
// come from its actor at 1/10 and 1/2 of the cells' budget T, `final` from the end of its run.
TEST(DatasetBuild, AReferenceLongerThanTheBudgetCheckpointsAtTheBudgetsFractions) {
  rapid::testing::ScratchDir dir;
  write_grid(dir.file("grid.json"), 400);
  nlohmann::json grid = nlohmann::json::parse(read_file(dir.file("grid.json")));
  grid["reference"]["steps"] = 3000;  // L; the cells' T is 2,000
  write_file_atomic(dir.file("grid.json"), grid.dump());
  const auto r = rapid_cli("dataset build --scenario pendulum --grid " + dir.file("grid.json") + " --dir " + dir.file("data"),
                           /*with_stderr=*/true);
  ASSERT_EQ(r.exit_code, 0) << r.text;
  const std::string out = dir.file("data/pendulum");
  for (const char* f : {"reference/actor_200.ckpt", "reference/actor_1000.ckpt", "reference/actor.ckpt"})
    EXPECT_TRUE(fs::exists(out + "/" + f)) << f;
  const auto record = nlohmann::json::parse(read_file(out + "/reference/record.json"));
  EXPECT_EQ(record["config"]["steps"], 3000);
  EXPECT_NE(read_dataset(out + "/medium.h5").metadata.at("source_checkpoint").find("actor_1000"), std::string::npos);
  EXPECT_NE(read_dataset(out + "/final.h5").metadata.at("source_checkpoint").find("step 3000"), std::string::npos);

  grid["reference"]["steps"] = 1500;  // below the cells' budget: refused before anything runs
  write_file_atomic(dir.file("grid.json"), grid.dump());
  const auto bad = rapid_cli("dataset build --scenario pendulum --grid " + dir.file("grid.json") + " --dir " + dir.file("d2"),
                             /*with_stderr=*/true);
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.text.find("reference.steps: 1500 is below the cells' budget of 2000 steps"), std::string::npos) << bad.text;
  EXPECT_FALSE(fs::exists(dir.file("d2")));
}

// The bug of the first flow reproduction: `initial` taken at T/10 before the reference's first
// update (warm-up 5,000 > 2,500) held the untrained actor. Such a build is refused before anything
// runs, from `dataset build` and from a sweep; and a checkpoint that says it had no update is
// refused when it is rolled out.
TEST(DatasetBuild, ASourceBeforeTheFirstUpdateIsRefused) {
  rapid::testing::ScratchDir dir;
  write_grid(dir.file("grid.json"), 400);
  nlohmann::json grid = nlohmann::json::parse(read_file(dir.file("grid.json")));
  grid["config"]["warmup_steps"] = 500;  // initial at 200 precedes the first update at 500
  write_file_atomic(dir.file("grid.json"), grid.dump());
  const std::string message =
      "the reference's initial actor (decision 200 of the budget of 2000) precedes its first update (decision 500: "
      "warmup_steps 500, batch_size 128) and would be untrained";
  const auto bad = rapid_cli("dataset build --scenario pendulum --grid " + dir.file("grid.json") + " --dir " + dir.file("d"),
                             /*with_stderr=*/true);
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.text.find(message), std::string::npos) << bad.text;
  EXPECT_EQ(std::count(bad.text.begin(), bad.text.end(), '\n'), 1) << bad.text;
  EXPECT_FALSE(fs::exists(dir.file("d")));
  const auto sweep = rapid_cli("sweep " + dir.file("grid.json") + " --out " + dir.file("s"), /*with_stderr=*/true);
  EXPECT_EQ(sweep.exit_code, 2);
  EXPECT_NE(sweep.text.find(message), std::string::npos) << sweep.text;
  EXPECT_FALSE(fs::exists(dir.file("s")));

  // Without a warm-up the first update is at the first full batch (128 online decisions).
  grid["config"]["warmup_steps"] = 0;
  grid["config"]["steps"] = 1000;  // initial at 100
  write_file_atomic(dir.file("grid.json"), grid.dump());
  const auto no_warmup = rapid_cli("dataset build --scenario pendulum --grid " + dir.file("grid.json") + " --dir " +
                                   dir.file("d"), /*with_stderr=*/true);
  EXPECT_EQ(no_warmup.exit_code, 2);
  EXPECT_NE(no_warmup.text.find("precedes its first update (decision 128: warmup_steps 0, batch_size 128)"),
            std::string::npos) << no_warmup.text;

  // A reference checkpoint that had no update, as a build of an earlier version could leave it.
  grid["config"]["steps"] = 2000;
  grid["config"]["warmup_steps"] = 200;
  write_file_atomic(dir.file("grid.json"), grid.dump());
  const std::string cmd = "dataset build --scenario pendulum --grid " + dir.file("grid.json") + " --dir " + dir.file("d");
  ASSERT_EQ(rapid_cli(cmd + " --reference-only").exit_code, 0);
  const std::string ckpt = dir.file("d/pendulum/reference/actor_200.ckpt");
  Mlp::load(ckpt).save(ckpt, 0);
  const auto stale = rapid_cli(cmd, /*with_stderr=*/true);
  ASSERT_EQ(stale.exit_code, 0) << stale.text;  // not trusted: the reference is trained again
  std::int64_t updates = -1;
  Mlp::load(ckpt, &updates);
  EXPECT_EQ(updates, 1);
  EXPECT_NE(stale.text.find("training the reference agent"), std::string::npos) << stale.text;
}

// A dataset that does not validate (here cut short, as a full disk or a copy can leave it) is not
// up to date: the build writes it again instead of keeping it. The reference is kept.
TEST(DatasetBuild, ATruncatedDatasetIsBuiltAgain) {
  rapid::testing::ScratchDir dir;
  write_grid(dir.file("grid.json"), 400);
  const std::string cmd = "dataset build --scenario pendulum --grid " + dir.file("grid.json") + " --dir " + dir.file("data");
  ASSERT_EQ(rapid_cli(cmd).exit_code, 0);
  const std::string out = dir.file("data/pendulum");
  const auto ref_time = mtime(out + "/reference/record.json");
  fs::resize_file(out + "/medium.h5", fs::file_size(out + "/medium.h5") / 2);
  const auto again = rapid_cli(cmd, /*with_stderr=*/true);
  ASSERT_EQ(again.exit_code, 0) << again.text;
  EXPECT_EQ(read_dataset(out + "/medium.h5", {3, 1, "pendulum"}).size(), 400u);
  EXPECT_EQ(mtime(out + "/reference/record.json"), ref_time);
}

// A disk that fills up while the datasets are written: exit 1 with one line naming the file and
// no temporary left (HDF5's own error path crashed, SIGSEGV). A file-size limit (RLIMIT_FSIZE,
// with SIGXFSZ ignored) fails the write as a full disk does, without a disk to fill.
TEST(DatasetBuild, AWriteThatFailsExitsOneInOneLineAndLeavesNoTemporary) {
  rapid::testing::ScratchDir dir;
  write_grid(dir.file("grid.json"), 20000);  // about 700 KB per dataset
  const std::string cmd = "dataset build --scenario pendulum --grid " + dir.file("grid.json") + " --dir " + dir.file("data");
  ASSERT_EQ(rapid_cli(cmd + " --reference-only").exit_code, 0);
  const std::string limited = "trap '' XFSZ; ulimit -f 500; exec '" + std::string(RAPID_BIN) + "' " + cmd + " 2>&1";
  std::string text;
  FILE* pipe = ::popen(limited.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  char buf[4096];
  for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, pipe)) > 0;) text.append(buf, n);
  const int status = ::pclose(pipe);
  ASSERT_TRUE(WIFEXITED(status)) << "killed by signal " << WTERMSIG(status) << "\n" << text;
  EXPECT_EQ(WEXITSTATUS(status), 1) << text;
  const std::string out = dir.file("data/pendulum");
  EXPECT_EQ(text.rfind("rapid: failed: cannot write dataset " + out + "/initial.h5: ", 0), 0u) << text;
  EXPECT_NE(text.find("File too large"), std::string::npos) << text;
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 1) << text;
  for (const auto& entry : fs::directory_iterator(out)) {
    const std::string name = entry.path().filename().string();
    EXPECT_EQ(name.find(".tmp"), std::string::npos) << name;
    EXPECT_NE(entry.path().extension(), ".h5") << name;
  }
  EXPECT_FALSE(fs::exists(out + "/build.json"));
}

TEST(DatasetBuild, BadInputExitsTwo) {
  rapid::testing::ScratchDir dir;
  const auto r = rapid_cli("dataset build --scenario nowhere --dir " + dir.file("d"), /*with_stderr=*/true);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.text.find("unknown scenario 'nowhere'"), std::string::npos) << r.text;
  const auto g = rapid_cli("dataset build --scenario pendulum --grid " + dir.file("missing.json") + " --dir " + dir.file("d"),
                           /*with_stderr=*/true);
  EXPECT_EQ(g.exit_code, 2) << g.text;
  EXPECT_FALSE(fs::exists(dir.file("d")));
}
