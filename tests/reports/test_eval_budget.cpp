// The evaluation budget (report/eval_budget.hpp): the cheapest number of episodes against its
// closed form, and the variance components recovered from runs drawn with known ones, the
// evaluation seeds shared by every run as the trainer shares them.
#include <gtest/gtest.h>

#include <cmath>

#include "core/rng.hpp"
#include "experiments/report/decide_replay.hpp"
#include "experiments/report/eval_budget.hpp"

namespace rapid {
namespace {

// Minimising (c0 + c·k)(B + I/k) over real k gives k* = √(I·c0 / (B·c)) (two-stage sampling).
TEST(EvalBudget, CheapestEpisodesIsTheTwoStageOptimum) {
  for (const auto& [c0, c, b, i] : {std::tuple{100.0, 1.0, 50.0, 200.0}, {10.0, 2.0, 5.0, 1000.0}, {60.0, 0.8, 8000.0, 6000.0}}) {
    const double real = std::sqrt(i * c0 / (b * c));
    const int k = cheapest_episodes(c0, c, b, i, 1000);
    EXPECT_LE(std::abs(k - real), 1.0) << c0 << " " << c << " " << b << " " << i;
  }
  EXPECT_EQ(cheapest_episodes(10.0, 1.0, 0.0, 5.0, 40), 40);  // no spread between runs: every episode counts
  EXPECT_EQ(cheapest_episodes(10.0, 1.0, 5.0, 0.0, 40), 1);   // no episode noise: one is enough
}

// 8 cells × 40 runs; a run's true return varies by training seed (variance 400), each evaluation
// seed has an effect shared by every run (variance 900, which cancels between runs) and a part
// that differs from run to run (variance 2500). The fit must find between ≈ 400 and interaction
// ≈ 2500, not the 3400 that one run's episodes spread by. The bounds are about three standard
// errors of the pooled variances (40 runs a cell, 8 cells).
TEST(EvalBudget, RecoversTheComponentsFromRunsThatShareEvaluationSeeds) {
  Rng rng(3);
  std::vector<double> seed_effect(30);
  for (double& e : seed_effect) e = rng.normal(0.0, 30.0);
  std::vector<EvalRun> runs;
  for (int cell = 0; cell < 8; ++cell)
    for (int seed = 0; seed < 40; ++seed) {
      EvalRun r;
      r.cell = "merge/initial/algo" + std::to_string(cell);
      const double truth = 100.0 * cell + rng.normal(0.0, 20.0);
      for (int k = 0; k < 30; ++k) r.final_episodes.push_back(truth + seed_effect[k] + rng.normal(0.0, 50.0));
      r.curve_steps = {0, 500, 1000};
      r.curve_mean = {0.0, truth / 2, truth};
      r.curve_std = {10.0, 10.0, 10.0};
      r.wall_s = 100.0;
      r.eval_s = 50.0;
      r.curve_episodes = 10;
      r.final_episodes_setting = 30;
      r.eval_every = 500;
      r.steps = 1000;
      runs.push_back(r);
    }
  const std::vector<EvalBudget> b = eval_budgets(runs);
  ASSERT_EQ(b.size(), 1u);
  EXPECT_EQ(b[0].cells, 8);
  EXPECT_NEAR(b[0].between, 400.0, 150.0);
  EXPECT_NEAR(b[0].interaction, 2500.0, 600.0);
  EXPECT_NEAR(b[0].within, 3400.0, 500.0);
  EXPECT_DOUBLE_EQ(b[0].train_s, 50.0);
  EXPECT_DOUBLE_EQ(b[0].episode_s, 50.0 / (2 * 10 + 30));  // the last point's 10 are the final 30's first
  // The recommendation is the two-stage optimum at the fitted components, the curve held.
  const double fixed_s = 50.0 + b[0].episode_s * 2 * b[0].recommended_curve;
  EXPECT_EQ(b[0].recommended_final, cheapest_episodes(fixed_s, b[0].episode_s, b[0].between, b[0].interaction, 100));
}

TEST(EvalBudget, RunsOfDifferentProtocolsAreRefused) {
  EvalRun a;
  a.cell = "merge/initial/x";
  a.final_episodes = {1, 2, 3};
  a.curve_steps = {0, 1};
  a.curve_mean = {0, 1};
  a.curve_std = {0, 0};
  a.curve_episodes = 10;
  a.final_episodes_setting = 3;
  EvalRun b = a;
  b.curve_episodes = 5;
  EXPECT_THROW(eval_budgets({a, b}), std::invalid_argument);
}

// `rapid replay-decide --run-times`: runs priced per scenario, and with the evaluation budget at
// equal precision each run counts its cost ÷ the precision a core-second gains (×2 precision per
// core-second: half the core-hours for the same variance of a cell mean).
TEST(EvalBudget, PricesRunsPerScenarioAndAtEqualPrecision) {
  const std::map<std::string, ScenarioRunCost> costs{{"a", {.run_s = 3600, .recommended_s = 1800, .precision_gain = 2.0}},
                                                     {"b", {.run_s = 360, .recommended_s = 360, .precision_gain = 1.0}}};
  const PricedRuns p = price_runs({{"a", 10}, {"b", 20}}, costs);
  EXPECT_DOUBLE_EQ(p.hours, 10.0 + 2.0);
  EXPECT_DOUBLE_EQ(p.hours_with_eval_budget, 5.0 + 2.0);
  EXPECT_DOUBLE_EQ(price_runs({}, costs).hours, 0.0);
  try {
    price_runs({{"c", 1}}, costs);
    ADD_FAILURE() << "a scenario without a cost was priced";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "no run time measured for scenario 'c'");
  }
}

}  // namespace
}  // namespace rapid
