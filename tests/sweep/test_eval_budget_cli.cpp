// `rapid eval-budget SWEEP_DIR` on a real sweep's records: the components and the recommendation
// per scenario, printed, and written only into --out (never into the folder it reads, issue #67);
// a sweep whose runs have no final evaluation to measure the episodes' share from is refused with
// one line.
#include <gtest/gtest.h>

#include "tests/datasets/dataset_fixtures.hpp"
#include "tests/sweep/sweep_test_util.hpp"

namespace rapid {
namespace {

using namespace sweep_test;

TEST(EvalBudgetCli, MeasuresASweepAndRefusesOneWithoutAFinalEvaluation) {
  testing::ScratchDir dir;
  const fs::path grid = dir.path() / "g.json", sweep = dir.path() / "sweep";
  nlohmann::json g = pendulum_grid("g", {"ddpg", "rapid-rl"}, {0, 1, 2}, 400);
  write_json(grid, g);
  ASSERT_EQ(run_rapid("sweep " + grid.string() + " --jobs 2 --no-summary --out " + sweep.string()).exit_code, 0);
  const Result none = run_rapid("eval-budget " + sweep.string());
  EXPECT_EQ(none.exit_code, 2) << none.output;
  EXPECT_NE(none.output.find("pendulum: the records need a final evaluation of at least 2 episodes"), std::string::npos)
      << none.output;
  EXPECT_FALSE(fs::exists(sweep / "eval-budget.md"));

  g["config"]["final_eval_episodes"] = 6;
  write_json(grid, g);
  const fs::path with = dir.path() / "with";
  ASSERT_EQ(run_rapid("sweep " + grid.string() + " --jobs 2 --no-summary --out " + with.string()).exit_code, 0);
  const Result printed = run_rapid("eval-budget " + with.string());
  ASSERT_EQ(printed.exit_code, 0) << printed.output;
  EXPECT_NE(printed.output.find("| pendulum | 6 (2) |"), std::string::npos) << printed.output;
  EXPECT_FALSE(fs::exists(with / "eval-budget.md")) << "written only where --out says";
  const fs::path report = dir.path() / "report";
  const Result r = run_rapid("eval-budget " + with.string() + " --out " + report.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("| pendulum | 6 (2) |"), std::string::npos) << r.output;
  const nlohmann::json j = read_json(report / "eval-budget.json");
  ASSERT_EQ(j.size(), 1u);
  EXPECT_EQ(j[0]["now"]["final_episodes"], 6);
  EXPECT_EQ(j[0]["now"]["points"], 3);  // steps 0, 200 and 400
  EXPECT_GE(j[0]["recommended"]["final_episodes"].get<int>(), 1);
  EXPECT_GT(j[0]["episode_s"].get<double>(), 0.0);

  const Result not_a_sweep = run_rapid("eval-budget " + dir.path().string());
  EXPECT_EQ(not_a_sweep.exit_code, 2);
  EXPECT_NE(not_a_sweep.output.find("SWEEP_DIR: "), std::string::npos) << not_a_sweep.output;
}

}  // namespace
}  // namespace rapid
