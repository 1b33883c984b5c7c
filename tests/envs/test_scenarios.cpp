// What makes each scenario the scenario docs/scenarios.md describes.
#include <gtest/gtest.h>

#include <libsumo/libsumo.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "envs/driving_env.hpp"
#include "envs/scenario_hooks.hpp"
#include "tests/envs/driving_test_util.hpp"

namespace rapid {
namespace {

TEST(Merge, EgoAlwaysStartsOnTheOnRamp) {
  auto env = test::make_driving("merge");
  Vec obs(env->obs_dim());
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    env->reset(seed, obs);
    EXPECT_EQ(env->ego_edge(), "ramp");
    EXPECT_LT(obs[DrivingEnv::kCommonObs], 1.0f);  // distance to the acceleration lane's end
  }
  // The acceleration lane ends; the main road's lanes run on.
  const Road::Edge& acc = env->road().edge("acc");
  EXPECT_EQ(acc.lanes, 3);
  EXPECT_NE(acc.lane_end[0], Road::kNoEnd);
  EXPECT_EQ(acc.lane_end[1], Road::kNoEnd);
  EXPECT_EQ(acc.lane_end[2], Road::kNoEnd);
}

TEST(Merge, SumoDriverMergesBeforeTheLaneEnds) {
  auto env = test::make_driving("merge");
  env->set_builtin_driver(true);
  Vec obs(env->obs_dim()), action = Vec::Zero(2);
  env->reset(4, obs);
  for (int t = 0; t < 60; ++t) ASSERT_FALSE(env->step(action, obs).terminated);
  EXPECT_GT(env->ego().global_lane, 0);
  EXPECT_EQ(obs[DrivingEnv::kCommonObs], 1.0f);
}

TEST(LaneDrop, DownstreamSectionHasFewerLanes) {
  auto env = test::make_driving("lane-drop");
  Vec obs(env->obs_dim());
  env->reset(1, obs);
  const Road::Edge& in = env->road().edge("in");
  const Road::Edge& out = env->road().edge("out");
  EXPECT_EQ(in.lanes, 3);
  EXPECT_EQ(out.lanes, 2);
  EXPECT_DOUBLE_EQ(in.lane_end[0], out.offset);  // the rightmost lane ends at the drop
  EXPECT_EQ(in.lane_end[1], Road::kNoEnd);
}

TEST(LaneDrop, TrafficIsCongested) {
  // The inflow exceeds what two lanes carry: the humans ahead of the ego are well below the
  // ego's desired speed on average.
  auto env = test::make_driving("lane-drop");
  env->set_builtin_driver(true);
  Vec obs(env->obs_dim()), action = Vec::Zero(2);
  env->reset(2, obs);
  for (int t = 0; t < 80; ++t) env->step(action, obs);
  double sum = 0.0;
  int n = 0;
  for (const auto& id : libsumo::Edge::getLastStepVehicleIDs("in")) sum += libsumo::Vehicle::getSpeed(id), ++n;
  ASSERT_GT(n, 30);
  EXPECT_LT(sum / n, 0.8 * env->settings().desired_speed);
}

TEST(CutIn, ObstaclesAreSlowerThanTheDesiredSpeedAndCutIn) {
  auto env = make_driving_env("cut-in", default_scenario_settings("cut-in"));
  const auto& obstacles = dynamic_cast<const CutInObstacles&>(*env->hook());
  env->set_builtin_driver(true);
  Vec obs(env->obs_dim()), action = Vec::Zero(2);
  int cut_ins = 0;
  for (std::uint64_t seed = 1; seed <= 4 && cut_ins == 0; ++seed) {
    env->reset(seed, obs);
    for (double v : obstacles.obstacle_speeds()) EXPECT_LT(v, env->settings().desired_speed - 5.0);
    for (bool done = false; !done;) {
      const StepResult r = env->step(action, obs);
      done = r.terminated || r.truncated;
      for (std::size_t k = 0; k < obstacles.obstacle_speeds().size(); ++k) {
        const std::string id = "obs" + std::to_string(k);
        EXPECT_LE(libsumo::Vehicle::getSpeed(id), obstacles.obstacle_speeds()[k] + 1e-6);
      }
    }
    cut_ins += obstacles.completed_cut_ins();
  }
  EXPECT_GT(cut_ins, 0) << "no obstacle cut into the ego's lane";
}

}  // namespace
}  // namespace rapid

namespace rapid {
namespace {

// Issue #67: the route file's name was /tmp/rapid-<pid>-<n>-<file>, so a symlink planted there by
// anyone could redirect the write. Now the name is random and the file is created by the env alone
// (O_EXCL, 0600): a planted symlink at every old name is left alone, and the victim unchanged.
TEST(RouteFile, IsCreatedUnderANameNoOneCanPlantALinkAt) {
  namespace fs = std::filesystem;
  const fs::path victim = fs::temp_directory_path() / ("rapid-victim-" + std::to_string(::getpid()));
  { std::ofstream(victim) << "untouched"; }
  std::vector<fs::path> planted;
  for (int n = 0; n < 4; ++n) {
    planted.push_back(fs::temp_directory_path() / ("rapid-" + std::to_string(::getpid()) + "-" + std::to_string(n) + "-merge.rou.xml"));
    fs::remove(planted.back());
    fs::create_symlink(victim, planted.back());
  }
  std::string made;
  {
    auto env = test::make_driving("merge");
    ASSERT_NE(env, nullptr);
    Vec obs(env->obs_dim());
    env->reset(0, obs);
    made = env->route_file();
    ASSERT_FALSE(made.empty());
    EXPECT_EQ(std::find(planted.begin(), planted.end(), fs::path(made)), planted.end());
    EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(made)));
    EXPECT_EQ(fs::status(made).permissions() & (fs::perms::group_all | fs::perms::others_all), fs::perms::none);
    std::ifstream routes(made);
    std::string xml((std::istreambuf_iterator<char>(routes)), std::istreambuf_iterator<char>());
    EXPECT_NE(xml.find("<routes"), std::string::npos);
    EXPECT_EQ(xml.find("\"INFLOW\""), std::string::npos);  // the inflows filled in
  }
  std::ifstream in(victim);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text, "untouched");
  EXPECT_FALSE(fs::exists(fs::symlink_status(made)));  // removed with the env
  for (const fs::path& p : planted) fs::remove(p);
  fs::remove(victim);
}

}  // namespace
}  // namespace rapid
