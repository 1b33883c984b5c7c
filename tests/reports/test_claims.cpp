// The claims check (C1–C6): records made to satisfy every claim pass; changing the numbers one
// claim rests on makes exactly that claim fail; a grid without what a claim needs gives N/A.
#include <gtest/gtest.h>

#include <map>

#include "experiments/report/claims_markdown.hpp"
#include "experiments/report/summarize.hpp"
#include "tests/datasets/dataset_fixtures.hpp"
#include "tests/reports/report_test_util.hpp"

namespace rapid {
namespace {

using report_test::BcPoint;
using report_test::CurvePoint;
using report_test::FakeRun;

const std::vector<std::string> kAlgos = {"rapid-rl", "rlpd", "col-prior", "col-all", "ddpg"};

class ClaimsTest : public ::testing::Test {
 protected:
  testing::ScratchDir scratch;
  std::filesystem::path sweep = scratch.path() / "sweep";
  // Mean final return per "dataset/algo" (ddpg: "/ddpg"), shaped like the paper's Table I.
  std::map<std::string, double> finals = {
      {"initial/rapid-rl", 100}, {"final+medium/rapid-rl", 110}, {"initial/rlpd", 80},  {"final+medium/rlpd", 85},
      {"initial/col-prior", 50}, {"final+medium/col-prior", 90}, {"initial/col-all", 10}, {"final+medium/col-all", 12},
      {"/ddpg", 60}};
  // How fast each algorithm gets there: the eval return at half the budget, as a share of its final.
  std::map<std::string, double> halfway_share = {{"rapid-rl", 0.9}, {"rlpd", 0.3}, {"col-prior", 0.3},
                                                 {"col-all", 0.3},  {"ddpg", 0.3}};
  bool swap_final_medium_bc = false;  // prior above online with final+medium
  bool flat_initial_bc = false;       // prior never crosses the online loss with initial
  std::vector<std::string> scenarios = {"merge"};
  std::vector<std::string> algos = kAlgos;

  std::vector<BcPoint> bc_curve(const std::string& dataset) const {
    std::vector<BcPoint> points;
    for (int i = 0; i <= 10; ++i) {
      const double step = 100.0 * i;
      if (dataset == "final+medium")
        points.push_back(swap_final_medium_bc ? BcPoint{step, 0.5, 0.1} : BcPoint{step, 0.1, 0.5});
      else
        points.push_back({step, flat_initial_bc ? 0.2 : 0.1 + 0.09 * i, 0.5});  // rises through 0.5
    }
    return points;
  }

  ClaimResult check(const std::string& id) {
    report_test::write_grid(sweep, report_test::make_grid("claims", scenarios, {"initial", "final+medium"}, algos, {0, 1}));
    for (const std::string& scenario : scenarios)
      for (const auto& [key, value] : finals) {
        const std::string dataset = key.substr(0, key.find('/')), algo = key.substr(key.find('/') + 1);
        if (std::find(algos.begin(), algos.end(), algo) == algos.end()) continue;
        for (std::uint64_t seed : {0u, 1u}) {
          FakeRun r;
          r.scenario = scenario;
          r.dataset = dataset;
          r.algo = algo;
          r.seed = seed;
          r.final_return = value + (seed == 0 ? -1.0 : 1.0);
          r.eval = {{0, 0.0}, {500, halfway_share.at(algo) * r.final_return}, {1000, r.final_return}};
          if (algo != "ddpg") r.bc = bc_curve(dataset);
          report_test::write_run(sweep, r);
        }
      }
    const Summary s = build_summary(sweep);
    for (const ClaimResult& c : s.claims)
      if (c.id == id) return c;
    ADD_FAILURE() << "no claim " << id;
    return {};
  }
};

TEST_F(ClaimsTest, AllClaimsPassOnPaperLikeRecords) {
  check("C1");
  const Summary s = build_summary(sweep);
  ASSERT_EQ(s.claims.size(), 6u);
  for (const ClaimResult& c : s.claims) EXPECT_EQ(c.verdict, "PASS") << c.id << ": " << c.reason;
  const std::string md = claims_markdown(s);
  // The decided verdicts lead (docs/decisions.md); the point-mean ones stay beside them, labelled,
  // with their definitions.
  EXPECT_NE(md.find("# Claims decided"), std::string::npos) << md;
  EXPECT_NE(md.find("Point-mean check (not a decision): PASS. On RAPID-RL's seed-mean BC-loss curves"), std::string::npos)
      << md;
}

TEST_F(ClaimsTest, C1FailsWhenRlpdIsBestInARow) {
  finals["initial/rlpd"] = 150;
  const ClaimResult c = check("C1");
  EXPECT_EQ(c.verdict, "FAIL");
  EXPECT_NE(c.reason.find("1/2 rows"), std::string::npos) << c.reason;
}

TEST_F(ClaimsTest, C2FailsWhenDdpgBeatsRapidRlOnTheInitialDataset) {
  EXPECT_EQ(check("C2").verdict, "PASS");
  finals["initial/rapid-rl"] = 55;
  EXPECT_EQ(check("C2").verdict, "FAIL");
}

TEST_F(ClaimsTest, C3FailsWhenColAllBeatsDdpgInOneRow) {
  finals["final+medium/col-all"] = 70;
  EXPECT_EQ(check("C3").verdict, "FAIL");
}

TEST_F(ClaimsTest, C4FailsWhenColPriorIsWorseWithBetterData) {
  finals["initial/col-prior"] = 95;
  EXPECT_EQ(check("C4").verdict, "FAIL");
}

TEST_F(ClaimsTest, C5FailsWhenAnotherAlgorithmLearnsFaster) {
  EXPECT_EQ(check("C5").verdict, "PASS");
  halfway_share["rapid-rl"] = 0.0;
  halfway_share["rlpd"] = 1.5;  // same final, much earlier
  EXPECT_EQ(check("C5").verdict, "FAIL");
  EXPECT_EQ(check("C1").verdict, "PASS");  // final means unchanged
}

TEST_F(ClaimsTest, C6FailsWhenPriorLossIsAboveOnlineWithGoodData) {
  swap_final_medium_bc = true;
  EXPECT_EQ(check("C6").verdict, "FAIL");
}

TEST_F(ClaimsTest, C6FailsWhenInitialPriorLossNeverRisesAboveOnline) {
  flat_initial_bc = true;
  const ClaimResult c = check("C6");
  EXPECT_EQ(c.verdict, "FAIL");
  ASSERT_EQ(c.rows.size(), 3u);
  EXPECT_EQ(c.rows[1].back(), "yes");  // first 20%: still below
  EXPECT_EQ(c.rows[2].back(), "no");   // last 20%: should be above
}

TEST_F(ClaimsTest, ClaimsAreNotApplicableWhenTheGridLacksWhatTheyNeed) {
  scenarios = {"pendulum"};
  algos = {"rapid-rl", "rlpd", "ddpg"};
  EXPECT_EQ(check("C6").verdict, "N/A");
  EXPECT_EQ(check("C3").verdict, "N/A");
  EXPECT_EQ(check("C4").verdict, "N/A");
  EXPECT_EQ(check("C2").verdict, "PASS");
}

TEST_F(ClaimsTest, AMissingCellCountsAgainstTheClaim) {
  check("C2");
  std::filesystem::remove(report_test::record_path(sweep, "merge", "", "ddpg", 0));
  std::filesystem::remove(report_test::record_path(sweep, "merge", "", "ddpg", 1));
  const Summary s = build_summary(sweep);
  EXPECT_EQ(s.claims[1].id, "C2");
  EXPECT_EQ(s.claims[1].verdict, "FAIL");
  EXPECT_EQ(s.claims[1].rows[0].back(), "no (no data)");
}

}  // namespace
}  // namespace rapid
