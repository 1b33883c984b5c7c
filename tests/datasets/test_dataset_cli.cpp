// `rapid dataset info`, run as a user would: the built binary, its stdout and exit code.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "core/dataset_io.hpp"
#include "core/dataset_stats.hpp"
#include "tests/cli_runner.hpp"
#include "tests/datasets/dataset_fixtures.hpp"
#include "tests/datasets/raw_d4rl_writer.hpp"

namespace rapid {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

using test::rapid_cli;

class DatasetInfoCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dataset_ = testing::make_dataset(4, 2, {30, 20, 25});
    dataset_.metadata[meta::kScenario] = "cut-in";
    write_dataset(dir_.file("d.h5"), dataset_);
  }
  testing::ScratchDir dir_;
  Dataset dataset_;
};

TEST_F(DatasetInfoCli, JsonHasTheSpecKeys) {
  const test::CliOutput out = rapid_cli("dataset info --json " + dir_.file("d.h5"));
  ASSERT_EQ(out.exit_code, 0) << out.text;
  const nlohmann::json j = nlohmann::json::parse(out.text);
  for (const char* key : {"transitions", "episodes", "return_mean", "return_std", "reward_mean", "reward_std",
                          "reward_histogram", "obs_dim", "act_dim", "metadata"})
    EXPECT_TRUE(j.contains(key)) << key;
  const DatasetStats s = dataset_stats(dataset_);
  EXPECT_EQ(j["transitions"], 75);
  EXPECT_EQ(j["episodes"], 3);
  EXPECT_EQ(j["obs_dim"], 4);
  EXPECT_EQ(j["act_dim"], 2);
  EXPECT_DOUBLE_EQ(j["return_mean"].get<double>(), s.return_mean);
  EXPECT_DOUBLE_EQ(j["reward_std"].get<double>(), s.reward_std);
  EXPECT_EQ(j["reward_histogram"]["counts"].size(), static_cast<std::size_t>(kDefaultHistogramBins));
  EXPECT_EQ(j["reward_histogram"]["edges"].size(), static_cast<std::size_t>(kDefaultHistogramBins) + 1);
  EXPECT_EQ(j["metadata"]["scenario"], "cut-in");
}

TEST_F(DatasetInfoCli, BinsAndSharedRange) {
  const test::CliOutput out = rapid_cli("dataset info --json --bins 3 --range -3 3 " + dir_.file("d.h5"));
  ASSERT_EQ(out.exit_code, 0) << out.text;
  const nlohmann::json j = nlohmann::json::parse(out.text);
  EXPECT_EQ(j["reward_histogram"]["edges"], (std::vector<double>{-3, -1, 1, 3}));
  EXPECT_EQ(j["reward_histogram"]["outside"], 0);
}

TEST_F(DatasetInfoCli, ImitatedSharePerEpsilonAndReturnHorizon) {
  const std::string file = dir_.file("d.h5");
  const std::vector<double> eps{-0.5, 0.25};
  for (int horizon : {1, 5}) {
    const test::CliOutput out = rapid_cli("dataset info --json --epsilon -0.5,0.25 --return-horizon " +
                                          std::to_string(horizon) + " " + file);
    ASSERT_EQ(out.exit_code, 0) << out.text;
    const nlohmann::json j = nlohmann::json::parse(out.text);
    EXPECT_EQ(j["imitated"]["return_window"], horizon);
    EXPECT_EQ(j["imitated"]["epsilon"], eps);
    EXPECT_EQ(j["imitated"]["share"], imitated_shares(dataset_, eps, horizon));
  }
  const test::CliOutput text = rapid_cli("dataset info --epsilon -0.5 --epsilon 0.25 " + file);
  ASSERT_EQ(text.exit_code, 0) << text.text;
  EXPECT_THAT(text.text, HasSubstr("imitated (mean reward over 1 decision of the episode > epsilon)"));
  EXPECT_THAT(text.text, HasSubstr("% of transitions"));
  const test::CliOutput alone = rapid_cli("dataset info --return-horizon 5 " + file, /*with_stderr=*/true);
  EXPECT_EQ(alone.exit_code, 2);
  EXPECT_THAT(alone.text, StartsWith("rapid: error: --return-horizon: only used with --epsilon"));
}

TEST_F(DatasetInfoCli, HumanReadableSummary) {
  const test::CliOutput out = rapid_cli("dataset info " + dir_.file("d.h5"));
  ASSERT_EQ(out.exit_code, 0) << out.text;
  EXPECT_THAT(out.text, HasSubstr("transitions 75, episodes 3"));
  EXPECT_THAT(out.text, HasSubstr("reward histogram (40 bins)"));
  EXPECT_THAT(out.text, HasSubstr("cut-in"));
}

TEST_F(DatasetInfoCli, BadFilesExitTwoWithOneLine) {
  std::filesystem::resize_file(dir_.file("d.h5"), std::filesystem::file_size(dir_.file("d.h5")) / 2);
  for (const std::string& file : {dir_.file("missing.h5"), dir_.file("d.h5")}) {
    const test::CliOutput out = rapid_cli("dataset info " + file, /*with_stderr=*/true);
    EXPECT_EQ(out.exit_code, 2) << out.text;
    EXPECT_THAT(out.text, StartsWith("rapid: error: dataset " + file + ": "));
    EXPECT_EQ(out.text.find('\n'), out.text.size() - 1) << "one line: " << out.text;
  }
}

// `rapid run --dataset F` refuses every file that does not fit its scenario the way `rapid
// dataset info` refuses a broken one: exit 2, one line naming the option and the file, and
// nothing written into --out (no failed record).
TEST(RunDatasetCli, AFileThatDoesNotFitIsBadInputAndNothingIsWritten) {
  testing::ScratchDir dir;
  // A pendulum-shaped dataset (obs_dim 3, act_dim 1) with actions inside [-1, 1].
  Dataset fits = testing::make_dataset(3, 1, {20, 20});
  fits.actions = fits.actions.cwiseMax(-1.0f).cwiseMin(1.0f);
  fits.metadata[meta::kScenario] = "pendulum";
  struct Case {
    std::string file, message;
  };
  std::vector<Case> cases;
  const auto raw = [&](const std::string& name, const std::vector<testing::KeyEdit>& edits, const std::string& message) {
    testing::write_raw_d4rl(dir.file(name), fits, edits);
    cases.push_back({name, message});
  };
  raw("nan.h5", {{.key = "observations", .nan_at = 4}}, "'observations' has a non-finite value");
  raw("float64.h5", {{.key = "rewards", .file_type = H5T_IEEE_F64LE}}, "'rewards' is float64, expected float32");
  raw("missing.h5", {{.key = "timeouts", .omit = true}}, "missing key 'timeouts'");
  raw("lengths.h5", {{.key = "actions", .dims = {39, 1}}}, "'actions' has 39 rows, 'observations' has 40");
  Dataset wide = fits;
  wide.actions(0, 3) = 1.5f;
  write_dataset(dir.file("wide.h5"), wide);
  cases.push_back({"wide.h5", "actions must lie in [-1, 1]"});
  Dataset obs = testing::make_dataset(4, 1, {20});
  write_dataset(dir.file("obs.h5"), obs);
  cases.push_back({"obs.h5", "'observations' has 4 columns, scenario pendulum expects 3"});
  Dataset other = fits;
  other.metadata[meta::kScenario] = "merge";
  write_dataset(dir.file("other.h5"), other);
  cases.push_back({"other.h5", "built for scenario 'merge', not 'pendulum'"});
  std::filesystem::create_symlink(dir.file("loop.h5"), dir.file("loop.h5"));
  cases.push_back({"loop.h5", "no dataset file at"});

  const std::string out = dir.file("job");
  for (const Case& c : cases) {
    const test::CliOutput r = rapid_cli("run --scenario pendulum --algo rapid-rl --seed 0 --set steps=300 --dataset " +
                                            dir.file(c.file) + " --out " + out,
                                        /*with_stderr=*/true);
    EXPECT_EQ(r.exit_code, 2) << c.file << "\n" << r.text;
    EXPECT_THAT(r.text, StartsWith("rapid: error: --dataset: ")) << c.file;
    EXPECT_THAT(r.text, HasSubstr(c.message)) << c.file;
    EXPECT_EQ(r.text.find('\n'), r.text.size() - 1) << "one line: " << r.text;
    EXPECT_FALSE(std::filesystem::exists(out)) << c.file;
  }
}

}  // namespace
}  // namespace rapid
