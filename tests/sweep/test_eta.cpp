// The sweep's ETA: each kind of job at its own measured rate (experiments/sweep/eta.hpp).
#include <gtest/gtest.h>

#include <cmath>

#include "experiments/sweep/eta.hpp"

namespace rapid {
namespace {

const CostKind kDdpgMerge{"merge", "ddpg"};
const CostKind kDdpgLaneDrop{"lane-drop", "ddpg"};
const CostKind kSacMerge{"merge", "rlpd-sac"};
const CostKind kSacLaneDrop{"lane-drop", "rlpd-sac"};
const CostKind kTd3BcCutIn{"cut-in", "td3-bc"};

TEST(SweepEta, UnknownUntilAJobHasFinished) {
  EtaModel eta;
  EXPECT_LT(eta.eta_s({{kDdpgMerge, 1000}}, 2), 0);
  eta.finished(kDdpgMerge, 1000, 10);
  EXPECT_DOUBLE_EQ(eta.eta_s({{kDdpgMerge, 1000}}, 1), 10);
  EXPECT_DOUBLE_EQ(eta.eta_s({}, 2), 0) << "nothing left";
}

// A grid mixing a cheap and a costly algorithm: the costly one's decisions are priced at its own
// rate, not at the mean rate per decision of all (which would say (5,000 × 0.205 s) / 2 = 512 s).
TEST(SweepEta, EachAlgorithmAtItsOwnRate) {
  EtaModel eta;
  eta.finished(kDdpgMerge, 1000, 10);   // 0.01 s per decision
  eta.finished(kSacMerge, 1000, 400);   // 0.4 s per decision
  const std::vector<WorkLeft> left{{kDdpgMerge, 1000}, {kDdpgMerge, 1000}, {kDdpgMerge, 1000},
                                   {kSacMerge, 1000}, {kSacMerge, 1000}};
  EXPECT_DOUBLE_EQ(eta.eta_s(left, 2), (3 * 10 + 2 * 400) / 2.0);
  EXPECT_DOUBLE_EQ(eta.eta_s(left, 1), 3 * 10 + 2 * 400);
}

// A kind not measured yet takes its algorithm's rate in the scenarios where that was measured,
// scaled by how the scenarios compare on the algorithms measured in both: rlpd-sac in lane-drop
// is its merge rate times lane-drop's DDPG over merge's DDPG. Costs multiply.
TEST(SweepEta, AnUnmeasuredKindCarriesItsAlgorithmOverFromAnotherScenario) {
  EtaModel eta;
  eta.finished(kDdpgMerge, 1000, 10);   // 0.01
  eta.finished(kSacMerge, 1000, 400);   // 0.4
  eta.finished(kDdpgLaneDrop, 1000, 30);  // 0.03
  EXPECT_DOUBLE_EQ(eta.seconds_per_unit(kSacLaneDrop), 0.4 * (0.03 / 0.01));
  // From two scenarios: the geometric mean of what each says.
  eta.finished({"cut-in", "ddpg"}, 1000, 20);       // 0.02
  eta.finished({"cut-in", "rlpd-sac"}, 1000, 600);  // 0.6
  EXPECT_NEAR(eta.seconds_per_unit(kSacLaneDrop), std::sqrt(1.2 * (0.6 * 0.03 / 0.02)), 1e-12);
  // The kind's own rate wins once it is measured.
  eta.finished(kSacLaneDrop, 1000, 500);
  EXPECT_DOUBLE_EQ(eta.seconds_per_unit(kSacLaneDrop), 0.5);
}

// Where nothing carries over: an algorithm measured nowhere costs what the median algorithm of
// its scenario does (not the pooled rate, which one costly algorithm dominates); an algorithm in
// a scenario with nothing in common, its own pooled rate; else all jobs' rate.
TEST(SweepEta, WhereNothingCarriesOverTheNearestMeasuredRate) {
  EtaModel eta;
  eta.finished(kDdpgMerge, 1000, 10);     // 0.01
  eta.finished({"merge", "rapid-rl"}, 1000, 12);  // 0.012
  eta.finished(kSacMerge, 1000, 400);     // 0.4
  EXPECT_DOUBLE_EQ(eta.seconds_per_unit({"merge", "td3-bc"}), 0.012) << "merge's median algorithm";
  EXPECT_DOUBLE_EQ(eta.seconds_per_unit({"cut-in", "rlpd-sac"}), 0.4) << "rlpd-sac's rate";
  EXPECT_DOUBLE_EQ(eta.seconds_per_unit(kTd3BcCutIn), 422.0 / 3000.0) << "all jobs' rate";
  eta.finished({"merge", "col-all"}, 1000, 14);  // an even count: the mean of the middle two
  EXPECT_DOUBLE_EQ(eta.seconds_per_unit({"merge", "td3-bc"}), (0.012 + 0.014) / 2);
}

// The tail of a sweep: one long job left cannot be shared among idle workers.
TEST(SweepEta, NeverLessThanTheLongestJobLeft) {
  EtaModel eta;
  eta.finished(kSacMerge, 1000, 400);
  EXPECT_DOUBLE_EQ(eta.eta_s({{kSacMerge, 1000}}, 2), 400);
  EXPECT_DOUBLE_EQ(eta.eta_s({{kSacMerge, 1000}, {kSacMerge, 500}}, 2), 400);
  EXPECT_DOUBLE_EQ(eta.eta_s({{kSacMerge, 1000}, {kSacMerge, 1000}, {kSacMerge, 1000}}, 2), 600);
}

}  // namespace
}  // namespace rapid
