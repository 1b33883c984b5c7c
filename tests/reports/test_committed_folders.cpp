// Issue #67: every subcommand that takes a results folder, run on each committed one without an
// output option, leaves it as it was: `summarize` refuses to turn its reports into a table of the
// no records it holds, `recheck` and `eval-budget` write only where --out says, the analyses
// print. The committed results are copied into a scratch folder and every file compared after.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "core/atomic_file.hpp"
#include "tests/cli_runner.hpp"
#include "tests/datasets/dataset_fixtures.hpp"

namespace rapid {
namespace {

namespace fs = std::filesystem;

// Every file under `root` by its path relative to it, with its bytes.
std::map<std::string, std::string> snapshot(const fs::path& root) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(root))
    if (entry.is_regular_file())
      files[fs::relative(entry.path(), root).string()] = read_file(entry.path().string(), std::uintmax_t{1} << 30);
  return files;
}

TEST(CommittedFolders, StayAsTheyAreUnderEverySubcommandWithoutAnOutputOption) {
  testing::ScratchDir scratch;
  const fs::path copy = scratch.path() / "results";
  fs::copy(fs::path(RAPID_SOURCE_DIR) / "results", copy, fs::copy_options::recursive);
  const std::map<std::string, std::string> before = snapshot(copy);

  std::vector<std::string> folders;  // committed results folders: reports without records
  for (const auto& entry : fs::recursive_directory_iterator(copy))
    if (entry.path().filename() == "summary.json" && !fs::exists(entry.path().parent_path() / "jobs"))
      folders.push_back(fs::relative(entry.path().parent_path(), scratch.path()).string());
  std::sort(folders.begin(), folders.end());
  ASSERT_GE(folders.size(), 10u);

  for (const std::string& f : folders) {
    const std::vector<std::string> commands = {"status " + f,
                                               "summarize " + f,
                                               "paper " + f,
                                               "beside " + f + " " + f,
                                               "replay-decide " + f,
                                               "simulate-decide " + f + " --experiments 3",
                                               "eval-budget " + f,
                                               "recheck " + f + " --seeds 100-100",
                                               "diff " + f + " results/baselines/paper-flow.json"};
    for (const std::string& command : commands) {
      const test::CliOutput out =
          test::shell_output("cd " + scratch.path().string() + " && " + RAPID_BIN + " " + command + " >/dev/null 2>&1");
      EXPECT_NE(out.exit_code, -1) << command;  // ended, by an exit code, not a signal
    }
    const test::CliOutput refused = test::shell_output("cd " + scratch.path().string() + " && " + RAPID_BIN +
                                                       " summarize " + f + " 2>&1");
    EXPECT_EQ(refused.exit_code, 2) << f << ": " << refused.text;
  }
  const std::map<std::string, std::string> after = snapshot(copy);
  for (const auto& [path, bytes] : after) {
    const auto it = before.find(path);
    EXPECT_TRUE(it != before.end()) << path << " was written";
    if (it != before.end()) EXPECT_TRUE(it->second == bytes) << path << " changed";
  }
  for (const auto& [path, bytes] : before) EXPECT_TRUE(after.count(path)) << path << " was removed";
  std::vector<std::string> beside;  // nothing new next to results/ either
  for (const auto& entry : fs::directory_iterator(scratch.path())) beside.push_back(entry.path().filename().string());
  EXPECT_EQ(beside, std::vector<std::string>{"results"});
}

}  // namespace
}  // namespace rapid
