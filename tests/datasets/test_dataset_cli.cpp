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

}  // namespace
}  // namespace rapid
