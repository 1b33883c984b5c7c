// Allocations of one env decision (docs/design.md §Performance rules: hot paths allocate nothing per step). libsumo's own
// allocations inside its calls are outside the harness's budget; they are counted and reported
// (as test properties and on stdout), split into SUMO's stepping and the env's state queries.
#include <gtest/gtest.h>

#include <cstdio>

#include "envs/driving_env.hpp"
#include "envs/env.hpp"
#include "envs/trace.hpp"
#include "tests/perf/library_alloc_counter.hpp"

using namespace rapid;

namespace {

// libsumo::Simulation::step(double): its allocations are SUMO's own simulation work.
constexpr const char* kSimulationStep = "_ZN7libsumo10Simulation4stepEd";

// Accelerate, brake, keep, and command left and right lane changes in turn, so every branch of
// a decision (including refused and impossible lane changes) runs while counting.
void action_for(int k, Vec& a) {
  static const float kAccel[] = {0.6f, -0.3f, 0.0f, 0.2f, -0.1f};
  static const float kLane[] = {0.0f, 0.9f, 0.0f, -0.9f, 0.0f};
  a[0] = kAccel[k % 5];
  a[1] = kLane[k % 5];
}

class EnvDecisionAllocation : public ::testing::TestWithParam<std::string> {};

}  // namespace

TEST_P(EnvDecisionAllocation, HarnessAllocatesNothingPerDecision) {
  std::unique_ptr<Env> env = make_env(GetParam());
  Vec obs(env->obs_dim()), action(env->act_dim());
  env->reset(3, obs);
  ASSERT_TRUE(test::watch_library("libsumocpp")) << "libsumo is not loaded";
  ASSERT_TRUE(test::watch_function(kSimulationStep));
  // Warm-up decisions: buffers that grow once (e.g. the ids of the neighbours) reach their size.
  int k = 0;
  bool over = false;
  for (; k < 3 && !over; ++k) {
    action_for(k, action);
    const StepResult r = env->step(action, obs);
    over = r.terminated || r.truncated;
  }
  ASSERT_FALSE(over) << "the episode ended during the warm-up; pick another seed";

  std::size_t harness = 0, libsumo = 0, stepping = 0;
  int decisions = 0;
  for (; decisions < 20 && !over; ++decisions, ++k) {
    action_for(k, action);
    test::start_counting();
    const StepResult r = env->step(action, obs);
    const test::AllocationCounts c = test::stop_counting();
    harness += c.outside_library();
    libsumo += c.in_library;
    stepping += c.in_function;
    over = r.terminated || r.truncated;
  }
  ASSERT_GT(decisions, 0);

  const double per_decision = static_cast<double>(libsumo) / decisions;
  const double stepping_per_decision = static_cast<double>(stepping) / decisions;
  std::printf("[ allocs   ] %s, per decision: harness %.2f, libsumo %.1f = SUMO stepping %.1f + the env's queries %.1f\n",
              GetParam().c_str(), static_cast<double>(harness) / decisions, per_decision, stepping_per_decision,
              per_decision - stepping_per_decision);
  RecordProperty("harness_allocations_per_decision", std::to_string(static_cast<double>(harness) / decisions));
  RecordProperty("libsumo_allocations_per_decision", std::to_string(per_decision));
  RecordProperty("sumo_stepping_allocations_per_decision", std::to_string(stepping_per_decision));
  EXPECT_EQ(harness, 0u) << "the env allocated outside libsumo during " << decisions << " decisions";
}

INSTANTIATE_TEST_SUITE_P(DrivingScenarios, EnvDecisionAllocation,
                         ::testing::Values("lane-drop", "cut-in", "merge"), [](const auto& info) {
                           std::string name = info.param;
                           for (char& c : name)
                             if (c == '-') c = '_';
                           return name;
                         });

// Recording off costs nothing (docs/traces.md): an env that recorded an episode and stopped makes
// exactly the libsumo queries of one that never recorded (counted by the allocations libsumo makes
// outside Simulation::step: its getters return strings and vectors) and allocates nothing itself;
// while recording, that count is visibly higher.
TEST(EnvDecisionAllocation, RecordingOffAddsNoLibsumoCallsAndNoAllocation) {
  auto count = [](Env& env, bool recording_before) {
    Trace trace;
    Vec obs(env.obs_dim()), action(env.act_dim());
    if (recording_before) {
      env.record(&trace);
      env.reset(4, obs);
      for (int k = 0; k < 3; ++k) {
        action_for(k, action);
        env.step(action, obs);
      }
      env.record(nullptr);
    }
    env.reset(3, obs);
    EXPECT_TRUE(test::watch_library("libsumocpp"));
    EXPECT_TRUE(test::watch_function(kSimulationStep));
    std::size_t harness = 0, libsumo = 0;
    for (int k = 0; k < 10; ++k) {
      action_for(k, action);
      test::start_counting();
      const StepResult r = env.step(action, obs);
      const test::AllocationCounts c = test::stop_counting();
      harness += c.outside_library();
      libsumo += c.in_library - c.in_function;  // the env's queries, not SUMO's stepping
      if (r.terminated || r.truncated) break;
    }
    return std::pair{harness, libsumo};
  };
  // First use of some libsumo queries in a process allocates once (a cache): warm them up.
  auto warm = make_env("merge");
  count(*warm, false);
  auto never = make_env("merge");
  const auto [never_harness, never_libsumo] = count(*never, false);
  auto stopped = make_env("merge");
  const auto [stopped_harness, stopped_libsumo] = count(*stopped, true);
  EXPECT_EQ(never_harness, 0u);
  EXPECT_EQ(stopped_harness, 0u);
  EXPECT_EQ(stopped_libsumo, never_libsumo) << "a decision with recording off called libsumo more";

  // While recording, the same decisions read every vehicle around the ego: more libsumo calls.
  auto recording = make_env("merge");
  Trace trace;
  recording->record(&trace);
  Vec obs(recording->obs_dim()), action(recording->act_dim());
  recording->reset(3, obs);
  std::size_t libsumo = 0;
  for (int k = 0; k < 10; ++k) {
    action_for(k, action);
    test::start_counting();
    const StepResult r = recording->step(action, obs);
    const test::AllocationCounts c = test::stop_counting();
    libsumo += c.in_library - c.in_function;
    if (r.terminated || r.truncated) break;
  }
  EXPECT_GT(libsumo, never_libsumo);
  std::printf("[ allocs   ] merge, 10 decisions: libsumo %zu unrecorded, %zu after recording stopped, %zu recording\n",
              never_libsumo, stopped_libsumo, libsumo);
}

// The attribution must see both kinds of allocation, or the test above proves nothing.
TEST(EnvDecisionAllocation, CounterSeesHarnessAndLibsumoAllocations) {
  std::unique_ptr<Env> env = make_env("merge");
  Vec obs(env->obs_dim());
  env->reset(1, obs);
  ASSERT_TRUE(test::watch_library("libsumocpp"));
  test::start_counting();
  std::vector<int> mine(100);
  const test::AllocationCounts harness = test::stop_counting();
  EXPECT_GE(harness.outside_library(), 1u);
  EXPECT_EQ(harness.in_library, 0u);
  test::start_counting();
  dynamic_cast<DrivingEnv&>(*env).advance_traffic_only(5);
  const test::AllocationCounts sumo = test::stop_counting();
  EXPECT_GE(sumo.in_library, 1u);
}
