// The flow profile's budget rule (docs/datasets.md) on curves whose answer is known by hand, and
// `rapid budget` on a folder of records.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "core/atomic_file.hpp"
#include "experiments/report/budget_rule.hpp"
#include "tests/cli_runner.hpp"
#include "tests/datasets/dataset_fixtures.hpp"

using namespace rapid;

namespace {

// Evaluations every 10 steps up to 200; returns from `f(step)`.
template <typename F>
ReferenceCurve curve(const std::string& label, F f) {
  ReferenceCurve c{label, {}, {}};
  for (long t = 0; t <= 200; t += 10) {
    c.steps.push_back(t);
    c.returns.push_back(f(t));
  }
  return c;
}

}  // namespace

TEST(BudgetRule, TIsTheFirstStepTheSmoothedMeanClosesSixtyPercentOfTheGap) {
  // Two seeds that rise linearly from 0 to 100 by step 100 and stay there: mean 0 → 100.
  const auto rise = [](long t) { return t >= 100 ? 100.0 : static_cast<double>(t); };
  const BudgetRuleResult r = apply_budget_rule({curve("a", rise), curve("b", rise)});
  EXPECT_DOUBLE_EQ(r.r0, 0.0);
  EXPECT_DOUBLE_EQ(r.plateau, 100.0);
  EXPECT_TRUE(r.plateaued);
  EXPECT_DOUBLE_EQ(r.threshold, 60.0);
  // s(t) = mean of c at t-20, t-10, t: s(70) = 60.
  EXPECT_EQ(r.budget, 70);
  EXPECT_EQ(r.long_run, 200);
}

TEST(BudgetRule, ACurveStillRisingInItsLastHalfFailsThePlateauCheck) {
  const BudgetRuleResult r = apply_budget_rule({curve("a", [](long t) { return static_cast<double>(t); })});
  EXPECT_FALSE(r.plateaued);
  // A curve that never learns has no gap to close.
  EXPECT_THROW(apply_budget_rule({curve("flat", [](long) { return 5.0; })}), std::invalid_argument);
  // Curves on different schedules cannot be averaged.
  ReferenceCurve shorter = curve("b", [](long) { return 1.0; });
  shorter.steps.pop_back();
  shorter.returns.pop_back();
  EXPECT_THROW(apply_budget_rule({curve("a", [](long t) { return 1.0 * t; }), shorter}), std::invalid_argument);
}

TEST(BudgetRule, TheCommandReadsTheRecordsOfAFolderPerScenario) {
  rapid::testing::ScratchDir dir;
  for (int seed = 0; seed < 2; ++seed) {
    nlohmann::json eval = nlohmann::json::array();
    for (long t = 0; t <= 200; t += 10) eval.push_back({{"target_step", t}, {"step", t + 3}, {"return_mean", t >= 100 ? 100.0 : 1.0 * t}});
    const nlohmann::json record = {{"status", "ok"}, {"cell", {{"scenario", "merge"}, {"algo", "ddpg"}, {"seed", seed}}}, {"eval", eval}};
    std::filesystem::create_directories(dir.file("runs/seed" + std::to_string(seed)));
    write_file_atomic(dir.file("runs/seed" + std::to_string(seed) + "/record.json"), record.dump());
  }
  // A record of another algorithm is not a reference run.
  std::filesystem::create_directories(dir.file("runs/other"));
  write_file_atomic(dir.file("runs/other/record.json"),
                    nlohmann::json({{"status", "ok"}, {"cell", {{"scenario", "merge"}, {"algo", "rlpd"}}}, {"eval", nlohmann::json::array()}}).dump());
  const auto ok = test::rapid_cli("budget " + dir.file("runs"));
  EXPECT_EQ(ok.exit_code, 0) << ok.text;
  EXPECT_NE(ok.text.find("merge: 2 reference run(s), L = 200, E = 10"), std::string::npos) << ok.text;
  EXPECT_NE(ok.text.find("T = 70"), std::string::npos) << ok.text;
  const auto missing = test::rapid_cli("budget " + dir.file("nothing"), /*with_stderr=*/true);
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.text.find("is not a folder"), std::string::npos) << missing.text;
}
