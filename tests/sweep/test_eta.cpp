// The sweep's ETA: each kind of job at its own measured rate (experiments/sweep/eta.hpp).
#include <gtest/gtest.h>

#include "experiments/sweep/eta.hpp"

namespace rapid {
namespace {

const JobKinds kDdpgMerge{"merge/ddpg", "ddpg"};
const JobKinds kSacMerge{"merge/rlpd-sac", "rlpd-sac"};
const JobKinds kSacLaneDrop{"lane-drop/rlpd-sac", "rlpd-sac"};
const JobKinds kTd3BcMerge{"merge/td3-bc", "td3-bc"};

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

// A kind not seen yet: the algorithm's rate in another scenario, else the mean of all finished jobs.
TEST(SweepEta, AnUnseenKindBorrowsTheNearestMeasuredRate) {
  EtaModel eta;
  eta.finished(kSacLaneDrop, 1000, 300);
  eta.finished(kDdpgMerge, 1000, 10);
  EXPECT_DOUBLE_EQ(eta.eta_s({{kSacMerge, 100}}, 1), 30) << "rlpd-sac's lane-drop rate";
  EXPECT_DOUBLE_EQ(eta.eta_s({{kTd3BcMerge, 100}}, 1), 100 * 310.0 / 2000.0) << "all jobs' rate";
  // The specific kind wins once it is measured.
  eta.finished(kSacMerge, 1000, 500);
  EXPECT_DOUBLE_EQ(eta.eta_s({{kSacMerge, 100}}, 1), 50);
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
