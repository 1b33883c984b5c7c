// Every algorithm keeps its bits: a short `rapid run` of each algorithm of the registry on
// pendulum and on lane-drop (SUMO) must make the same record and the same actor checkpoint as
// the digests in tests/golden/record-bits/. A refactoring that promises "behaviour kept bit for
// bit" (issues #41 and #43) is checked here rather than by reading; a change that means to move
// the numbers refreshes the digests on purpose:
//
//   RAPID_RECORD_BITS_WRITE=1 build/tests/run_tests --gtest_filter='RecordBits*'
//
// and says so in its commit. RAPID_RECORD_BITS_BIN=/path/to/rapid checks another binary against
// the same digests (an older build, to show two revisions agree). The digest covers what a run
// learned and measured (evaluations, final return, losses, BC losses, gradient norms, training
// episodes, update count) and the checkpoint's bytes, not times, hosts or paths.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "algos/registry.hpp"
#include "core/atomic_file.hpp"
#include "core/dataset.hpp"
#include "core/dataset_io.hpp"
#include "core/hash.hpp"
#include "envs/env.hpp"
#include "tests/cli_runner.hpp"
#include "tests/datasets/dataset_fixtures.hpp"
#include "tests/random_dataset.hpp"

namespace rapid {
namespace {

struct BitsCase {
  std::string scenario, algo;
};
void PrintTo(const BitsCase& c, std::ostream* os) { *os << c.scenario << "/" << c.algo; }

std::vector<BitsCase> every_case() {
  std::vector<BitsCase> cases;
  for (const std::string scenario : {"pendulum", "lane-drop"})
    for (const Algorithm& a : algorithms()) cases.push_back({scenario, a.name});
  return cases;
}

std::string digest_of_run(const std::string& job) {
  const nlohmann::json r = nlohmann::json::parse(read_file(job + "/record.json"));
  nlohmann::json learned;
  for (const char* key : {"status", "eval", "final", "losses", "bc_loss", "gradients", "train_episodes", "updates"})
    learned[key] = r.value(key, nlohmann::json());
  return fnv1a_hex(learned.dump()) + " " + fnv1a_hex(read_file(job + "/actor.ckpt"));
}

class RecordBits : public ::testing::TestWithParam<BitsCase> {};

TEST_P(RecordBits, TheRecordAndCheckpointAreTheDigestsOnFile) {
  const auto& [scenario, algo] = GetParam();
  const Algorithm& a = find_algorithm(algo);
  ::setenv("OMP_NUM_THREADS", "1", 1);
  rapid::testing::ScratchDir dir;
  std::string args = "run --scenario " + scenario + " --algo " + algo + " --seed 1 --out " + dir.file("job");
  if (a.uses_prior) {
    write_dataset(dir.file("prior.h5"), test::random_dataset(scenario, scenario == "pendulum" ? 600 : 200));
    args += " --dataset " + dir.file("prior.h5");
  }
  args += scenario == "pendulum" ? " --set steps=600 --set warmup_steps=100 --set eval_every=300 --set eval_episodes=1"
                                   " --set bc_log_every=100 --set batch_size=32"
                                 : " --set steps=60 --set warmup_steps=0 --set eval_every=60 --set eval_episodes=1"
                                   " --set bc_log_every=30 --set batch_size=16";
  if (a.uses_returns) args += " --set return_horizon=5";
  const char* other = std::getenv("RAPID_RECORD_BITS_BIN");
  const std::string command = std::string(other ? other : RAPID_BIN) + " " + args + " 2>&1";
  const int status = std::system(command.c_str());
  ASSERT_EQ(status, 0) << command;
  const std::string digest = digest_of_run(dir.file("job"));

  const std::filesystem::path file =
      std::filesystem::path(RAPID_SOURCE_DIR) / "tests" / "golden" / "record-bits" / (scenario + "-" + algo + ".txt");
  if (std::getenv("RAPID_RECORD_BITS_WRITE")) {
    write_file_atomic(file.string(), digest + "\n");
    GTEST_SKIP() << "wrote " << file;
  }
  ASSERT_TRUE(std::filesystem::exists(file)) << file << " is missing: a new algorithm writes its digests once with "
                                                     "RAPID_RECORD_BITS_WRITE=1 (see the top of this file)";
  EXPECT_EQ(digest + "\n", read_file(file.string()))
      << scenario << " / " << algo << ": the run no longer makes the bits on file. If that is the change's purpose, "
      << "refresh the digests (the top of tests/test_record_bits.cpp) and say so in the commit.";
}

INSTANTIATE_TEST_SUITE_P(EveryAlgorithm, RecordBits, ::testing::ValuesIn(every_case()), [](const auto& info) {
  std::string n = info.param.scenario + "_" + info.param.algo;
  for (char& c : n)
    if (c == '-') c = '_';
  return n;
});

}  // namespace
}  // namespace rapid
