// The paper beside us: Kendall's τ-b as scipy computes it, one row per row of ours that the paper
// has (DDPG's dataset-free cell in each), the right order read as agreement and the reverse as
// disagreement, and the permutation test holding its error rate when our orders are random.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>

#include "experiments/report/paper_ranking.hpp"

namespace rapid {
namespace {

TEST(PaperRanking, KendallTauBMatchesScipy) {
  // scipy.stats.kendalltau's documented example (ties on both sides): τ-b = −0.47140452079103173.
  EXPECT_NEAR(kendall_tau_b({12, 2, 1, 12, 2}, {1, 4, 7, 1, 0}), -0.47140452079103173, 1e-12);
  EXPECT_DOUBLE_EQ(kendall_tau_b({1, 2, 3, 4}, {10, 20, 30, 40}), 1.0);
  EXPECT_DOUBLE_EQ(kendall_tau_b({1, 2, 3, 4}, {4, 3, 2, 1}), -1.0);
  EXPECT_TRUE(std::isnan(kendall_tau_b({1, 1, 1}, {1, 2, 3})));
}

// Our rows: every (scenario, dataset) of the paper, each algorithm's finals spread around
// `scale` × the paper's mean (the paper's order kept when scale > 0, reversed when < 0).
std::vector<OurRow> rows_scaled(double scale) {
  std::vector<OurRow> rows;
  for (const PublishedCell& c : paper_table_i()) {
    auto it = std::find_if(rows.begin(), rows.end(), [&](const OurRow& r) { return r.scenario == c.scenario && r.dataset == c.dataset; });
    if (it == rows.end()) it = rows.insert(rows.end(), OurRow{c.scenario, c.dataset, {}});
    const double m = scale * c.mean;
    it->finals.emplace_back(c.algo, std::vector<double>{m - 0.1, m, m + 0.1});
  }
  return rows;
}

TEST(PaperRanking, TheSameOrderAgreesAndTheReverseDisagrees) {
  const std::optional<PaperAgreement> same = paper_agreement(rows_scaled(0.5));
  ASSERT_TRUE(same);
  ASSERT_EQ(same->rows.size(), 9u);
  // Merge's DDPG ties CoL-prior's Initial in the paper; ours does too here, so τ-b is 1 there as well.
  EXPECT_DOUBLE_EQ(same->mean_tau, 1.0);
  EXPECT_EQ(same->same_best, 9);
  EXPECT_LT(same->p_value, 1e-3);
  EXPECT_EQ(same->rows[0].paper.size(), 5u) << "lane-drop has RAPID-RL's published value";
  EXPECT_EQ(same->rows[3].paper.size(), 4u) << "cut-in has not";
  EXPECT_EQ(same->rows[0].paper.front().algo, "rapid-rl");

  const std::optional<PaperAgreement> reversed = paper_agreement(rows_scaled(-1.0));
  ASSERT_TRUE(reversed);
  EXPECT_DOUBLE_EQ(reversed->mean_tau, -1.0);
  EXPECT_EQ(reversed->same_best, 0);
  EXPECT_GT(reversed->p_value, 0.99);
}

TEST(PaperRanking, RowsThePaperDoesNotHaveAreLeftOut) {
  EXPECT_FALSE(paper_agreement({{"pendulum", "medium", {{"rapid-rl", {1.0}}, {"rlpd", {2.0}}, {"ddpg", {3.0}}}}}));
  // Two methods with a published value are too few to order.
  EXPECT_FALSE(paper_agreement({{"merge", "medium", {{"rlpd", {1.0}}, {"ddpg", {2.0}}, {"rlpd-sac", {3.0}}}}}));
  EXPECT_FALSE(paper_agreement({}));
}

TEST(PaperRanking, OurRowsComeFromSummaryJsonWithDdpgInEveryRow) {
  const nlohmann::json summary = {
      {"cells",
       {{{"scenario", "merge"}, {"dataset", "initial"}, {"algo", "rlpd"},
         {"seeds", {{{"seed", 0}, {"status", "ok"}, {"final", 5.0}}, {{"seed", 1}, {"status", "failed"}, {"final", nullptr}}}}},
        {{"scenario", "merge"}, {"dataset", nullptr}, {"algo", "ddpg"}, {"seeds", {{{"seed", 0}, {"status", "ok"}, {"final", 7.0}}}}}}},
      {"table",
       {{{"scenario", "merge"}, {"dataset", "initial"},
         {"columns", {{{"algo", "rlpd"}, {"cell", "merge/initial/rlpd"}}, {{"algo", "ddpg"}, {"cell", "merge/none/ddpg"}}}}},
        {{"scenario", "merge"}, {"dataset", "medium"}, {"columns", {{{"algo", "ddpg"}, {"cell", "merge/none/ddpg"}}}}}}}};
  const std::vector<OurRow> rows = our_rows(summary);
  ASSERT_EQ(rows.size(), 2u);
  ASSERT_EQ(rows[0].finals.size(), 2u);
  EXPECT_EQ(rows[0].finals[0].second, std::vector<double>{5.0}) << "only ok seeds";
  EXPECT_EQ(rows[1].finals[0].first, "ddpg");
  EXPECT_EQ(rows[1].finals[0].second, std::vector<double>{7.0});
}

TEST(PaperRanking, ThePermutationTestHoldsItsErrorRateWhenOurLabelsCarryNoInformation) {
  // Our results unrelated to the paper's but, as in a real grid, alike across a scenario's rows:
  // each method has a scenario-wide effect and a little row noise. p ≤ 0.05 should happen in at
  // most 5% of the draws (+ three binomial standard errors of the simulations). A test that
  // permuted each row on its own would take the rows for independent evidence and reject more often.
  std::mt19937_64 rng(17);
  std::normal_distribution<double> noise(0.0, 1.0);
  int rejected = 0;
  constexpr int kSimulations = 200;
  for (int i = 0; i < kSimulations; ++i) {
    std::vector<OurRow> rows = rows_scaled(1.0);
    std::map<std::string, double> effect;  // "scenario/algo" → its scenario-wide effect
    for (OurRow& r : rows)
      for (auto& [algo, finals] : r.finals) {
        const auto [it, drawn] = effect.try_emplace(r.scenario + "/" + algo, 0.0);
        if (drawn) it->second = noise(rng);
        finals = {it->second + 0.1 * noise(rng), it->second + 0.1 * noise(rng)};
      }
    const std::optional<PaperAgreement> a = paper_agreement(rows);
    ASSERT_TRUE(a);
    rejected += a->p_value <= 0.05 ? 1 : 0;
  }
  EXPECT_LE(rejected, 0.05 * kSimulations + 3 * std::sqrt(0.05 * 0.95 * kSimulations)) << rejected;
  EXPECT_GE(rejected, 1) << "a test that never rejects is not at its level either";
}

}  // namespace
}  // namespace rapid
